#include "parameters.hpp"

namespace clothlab {

std::string_view stage_name(stage_kind stage) {
  switch (stage) {
    case stage_kind::spring:
      return "spring";
    case stage_kind::coupled:
      return "coupled";
    case stage_kind::cloth:
      return "cloth";
  }
  return "?";
}

std::string_view integrator_name(integrator_kind kind) {
  switch (kind) {
    case integrator_kind::semi_implicit:
      return "semi-implicit";
    case integrator_kind::explicit_euler:
      return "explicit";
  }
  return "?";
}

}  // namespace clothlab
