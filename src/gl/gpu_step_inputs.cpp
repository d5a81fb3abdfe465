#include "gl/gpu_step_inputs.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace clothlab {
namespace {

// The bit of the offset (du, dv) in a mask: its index in neighbour_offsets. Every spring joins
// neighbours of the table.
int neighbour_bit(int du, int dv) {
  for (int bit = 0; bit < neighbour_count; ++bit) {
    const auto& offset = neighbour_offsets[static_cast<std::size_t>(bit)];
    if (offset[0] == du && offset[1] == dv)
      return bit;
  }
  throw std::logic_error("neighbour_bit: (" + std::to_string(du) + ", " + std::to_string(dv) +
                         ") is not a neighbour of the spring table");
}

}  // namespace

void spring_masks(const spring_mesh& cloth, std::vector<std::uint32_t>& masks) {
  const auto n = static_cast<std::uint32_t>(cloth.grid_size());
  masks.assign(static_cast<std::size_t>(n) * n, 0u);
  // Each spring of the cloth's lists (the intact ones) sets its bit at both of its ends.
  for (spring_family family : all_spring_families) {
    for (const spring& s : cloth.springs(family)) {
      const int du = static_cast<int>(s.b % n) - static_cast<int>(s.a % n);
      const int dv = static_cast<int>(s.b / n) - static_cast<int>(s.a / n);
      masks[s.a] |= 1u << neighbour_bit(du, dv);
      masks[s.b] |= 1u << neighbour_bit(-du, -dv);
    }
  }
}

std::array<float, 3> family_rest_lengths(const spring_mesh& cloth) {
  const int n = cloth.grid_size();
  const std::span<const double> x0 = cloth.rest_positions();
  // |x0(0, 0) - x0(du, dv)| for the first spring of each family; N = 2 has no bending spring
  // (none of its texels uses that length).
  const auto distance = [&](int du, int dv) {
    const std::size_t b = 3 * spring_mesh::index(std::min(du, n - 1), dv, n);
    return static_cast<float>(
        glm::length(glm::dvec3(x0[0], x0[1], x0[2]) - glm::dvec3(x0[b], x0[b + 1], x0[b + 2])));
  };
  return {distance(1, 0), distance(1, 1), distance(2, 0)};
}

void remove_torn_springs(std::span<const std::uint32_t> masks, spring_mesh& cloth) {
  const auto n = static_cast<std::uint32_t>(cloth.grid_size());
  // The bit of the spring from a to b in a's mask (both ends agree: the GPU tears both at once).
  const auto bit_of = [n](const spring& s) {
    return neighbour_bit(static_cast<int>(s.b % n) - static_cast<int>(s.a % n),
                         static_cast<int>(s.b / n) - static_cast<int>(s.a / n));
  };
  cloth.remove_springs_if([&](const spring& s) {
    const int i = bit_of(s);
    return (masks[s.a] & (1u << i)) == 0u;
  });
}

std::array<float, 3> tear_lengths(double strain, const std::array<float, 3>& rest_length) {
  std::array<float, 3> lengths{};
  for (std::size_t family = 0; family < 3; ++family)
    lengths[family] = static_cast<float>((1.0 + strain) * rest_length[family]);
  return lengths;
}

void step_uniforms::locate(const shader_program& program) {
  const auto at = [&](const char* name) { return program.uniform(name); };
  at_ = {.grid_size = at("grid_size"),
         .stiffness = at("stiffness"),
         .rest_length = at("rest_length"),
         .time_step = at("time_step"),
         .damping = at("damping"),
         .mass = at("mass"),
         .gravity = at("gravity"),
         .explicit_euler = at("explicit_euler"),
         .wind_strength = at("wind_strength"),
         .wind_direction = at("wind_direction"),
         .drag_enabled = at("drag_enabled"),
         .drag_texel = at("drag_texel"),
         .drag_target = at("drag_target"),
         .drag_stiffness = at("drag_stiffness"),
         .sphere_enabled = at("sphere_enabled"),
         .sphere_centre = at("sphere_centre"),
         .sphere_radius = at("sphere_radius"),
         .sphere_friction = at("sphere_friction"),
         .ground_enabled = at("ground_enabled"),
         .ground_height = at("ground_height"),
         .ground_friction = at("ground_friction")};
  sent_once_ = false;
}

void tear_uniform::set(const shader_program& tear_program, double strain,
                       const std::array<float, 3>& rest_length) {
  const std::array<float, 3> tear_length = tear_lengths(strain, rest_length);
  if (tear_length == sent_)
    return;
  tear_program.use();
  glUniform3fv(tear_program.uniform("tear_length"), 1, tear_length.data());
  sent_ = tear_length;
}

void step_uniforms::set(const cloth_parameters& p, int grid_size,
                        const std::array<float, 3>& rest_length) {
  const auto f = [](double x) { return static_cast<float>(x); };
  const auto f3 = [](const glm::dvec3& x) {
    return std::array<float, 3>{static_cast<float>(x.x), static_cast<float>(x.y),
                                static_cast<float>(x.z)};
  };
  const dynamics_parameters& d = p.dynamics;
  // u_w, a unit vector even without wind (K_w = 0 is what turns it off, as on the CPU), so that
  // the shader may normalize() it again: never a zero vector, whose normalize() is NaN. The
  // parameters' direction is never zero (the options and the window refuse it); were it zero,
  // the default direction stands in.
  const double wind_length = glm::length(p.wind_direction);
  const glm::dvec3 wind_unit =
      wind_length > 0.0 ? p.wind_direction / wind_length : cloth_parameters{}.wind_direction;
  const bool drag = p.drag.enabled && p.drag.ku >= 0 && p.drag.ku < grid_size && p.drag.kv >= 0 &&
                    p.drag.kv < grid_size;
  const values v = {
      .grid_size = grid_size,
      .stiffness = {f(p.structural_stiffness), f(p.shear_stiffness), f(p.bending_stiffness)},
      .rest_length = rest_length,
      .time_step = f(d.time_step),
      .damping = f(d.damping),
      .mass = f(d.mass),
      .gravity = f(d.gravity),
      .explicit_euler = d.integrator == integrator_kind::explicit_euler,
      .wind_strength = f(p.wind_strength),
      .wind_direction = f3(wind_unit),
      .drag_enabled = drag,
      .drag_texel = {p.drag.ku, p.drag.kv},
      .drag_target = f3(p.drag.target),
      .drag_stiffness = f(p.drag.stiffness),
      .sphere_enabled = p.sphere.enabled,
      .sphere_centre = f3(p.sphere.centre),
      .sphere_radius = f(p.sphere.radius),
      .sphere_friction = f(p.sphere.friction),
      .ground_enabled = p.ground_enabled,
      .ground_height = f(p.ground_height),
      .ground_friction = f(p.ground_friction)};
  if (sent_once_ && v == sent_)
    return;  // the program still holds them
  glUniform1i(at_.grid_size, v.grid_size);
  glUniform3fv(at_.stiffness, 1, v.stiffness.data());
  glUniform3fv(at_.rest_length, 1, v.rest_length.data());
  glUniform1f(at_.time_step, v.time_step);
  glUniform1f(at_.damping, v.damping);
  glUniform1f(at_.mass, v.mass);
  glUniform1f(at_.gravity, v.gravity);
  glUniform1i(at_.explicit_euler, v.explicit_euler);
  glUniform1f(at_.wind_strength, v.wind_strength);
  glUniform3fv(at_.wind_direction, 1, v.wind_direction.data());
  glUniform1i(at_.drag_enabled, v.drag_enabled);
  glUniform2iv(at_.drag_texel, 1, v.drag_texel.data());
  glUniform3fv(at_.drag_target, 1, v.drag_target.data());
  glUniform1f(at_.drag_stiffness, v.drag_stiffness);
  glUniform1i(at_.sphere_enabled, v.sphere_enabled);
  glUniform3fv(at_.sphere_centre, 1, v.sphere_centre.data());
  glUniform1f(at_.sphere_radius, v.sphere_radius);
  glUniform1f(at_.sphere_friction, v.sphere_friction);
  glUniform1i(at_.ground_enabled, v.ground_enabled);
  glUniform1f(at_.ground_height, v.ground_height);
  glUniform1f(at_.ground_friction, v.ground_friction);
  sent_ = v;
  sent_once_ = true;
}

}  // namespace clothlab
