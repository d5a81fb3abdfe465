// The stand-in for XPBD (xpbd.hpp) where it is not built: the student copy has no xpbd.cpp (XPBD
// steps the cloth from its springs and their rest lengths, and computes the wind: a student
// could run the cloth with it instead of answering questions 8 and 13). It says so, and every
// function that would run XPBD throws.
#include <stdexcept>

#include "core/xpbd.hpp"

namespace clothlab {

bool xpbd_available() {
  return false;
}

const char* xpbd_unavailable_reason() {
  return "XPBD (--integrator xpbd) is in the teacher's copy: it steps the cloth from its springs "
         "itself; use another integrator";
}

int cloth_constraint_colour(const spring&, int) {
  throw std::invalid_argument(xpbd_unavailable_reason());
}

void xpbd_cloth_external_force(const cloth_parameters&, std::span<const double>,
                               std::span<const std::uint8_t>, std::vector<double>&,
                               std::span<double>) {
  throw std::invalid_argument(xpbd_unavailable_reason());
}

void xpbd_solver::step(const dynamics_parameters&, const force_model&, particle_system&) {
  throw std::invalid_argument(xpbd_unavailable_reason());
}

}  // namespace clothlab
