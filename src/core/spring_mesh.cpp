#include "spring_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "integrator.hpp"

namespace clothlab {
namespace {

// The springs of the handout's figure 6 as data: each (du, dv) joins (ku, kv) to
// (ku + du, kv + dv), so that every spring is counted once and acts on both of its ends.
struct spring_offset {
  spring_family family;
  int du;
  int dv;
};
constexpr spring_offset spring_offsets[] = {
    {spring_family::structural, 1, 0},  // (ku, kv)-(ku+1, kv), rest length h
    {spring_family::structural, 0, 1},  // (ku, kv)-(ku, kv+1), rest length h
    {spring_family::shear, 1, 1},       // (ku, kv)-(ku+1, kv+1), rest length h sqrt(2)
    {spring_family::shear, -1, 1},      // (ku, kv)-(ku-1, kv+1), the other diagonal
    {spring_family::bending, 2, 0},     // (ku, kv)-(ku+2, kv), rest length 2h
    {spring_family::bending, 0, 2},     // (ku, kv)-(ku, kv+2), rest length 2h
};

}  // namespace

spring_mesh::spring_mesh(const cloth_parameters& p) : parameters(p) {
  load_model();
}

cloth_parameters spring_mesh::effective_parameters() const {
  cloth_parameters built = parameters;
  built.grid_size = grid_size_;
  return effective_cloth_parameters(built);
}

double spring_mesh::stiffness(spring_family family) const {
  const cloth_parameters effective = effective_parameters();
  switch (family) {
    case spring_family::structural:
      return effective.structural_stiffness;
    case spring_family::shear:
      return effective.shear_stiffness;
    case spring_family::bending:
      return effective.bending_stiffness;
  }
  return 0.0;
}

std::array<spring_set, 3> spring_mesh::spring_sets() const {
  std::array<spring_set, 3> sets{};
  for (spring_family family : all_spring_families)
    sets[static_cast<int>(family)] = {springs(family), stiffness(family)};
  return sets;
}

force_model spring_mesh::forces(const std::array<spring_set, 3>& sets) {
  force_model model{sets, {}};
  if (parameters.wind_strength != 0.0) {
    model.add_other_forces = [this](std::span<const double> position, std::span<double> force) {
      // The normals of the positions the forces are evaluated at: at the current state they are
      // the cloth's own normals(), at an integrator's intermediate state a scratch array.
      const bool current_state = position.data() == particles_.position.data();
      std::vector<double>& normal = current_state ? normals_ : stage_normals_;
      normal.resize(position.size());
      compute_vertex_normals(grid_size_, position, normal);
      accumulate_wind_forces(parameters.wind_strength, parameters.wind_direction, normal, force);
    };
  }
  return model;
}

void spring_mesh::load_model() {
  const int n = std::max(parameters.grid_size, 2);
  const double side = parameters.side_length;
  const double h = side / (n - 1);  // rest distance between grid neighbours
  grid_size_ = n;
  particles_.resize(static_cast<std::size_t>(n) * n);
  normals_.assign(3 * particles_.size(), 0.0);

  // Flat, at rest: p(ku, kv) = (-S/2 + ku h, -S/2 + kv h, 0).
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      particles_.set_position(index(ku, kv, n), {-side / 2 + ku * h, -side / 2 + kv * h, 0.0});
    }
  }

  // Rest lengths are the distances in this initial configuration.
  for (auto& family : springs_)
    family.clear();
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      for (const spring_offset& o : spring_offsets) {
        const int ku2 = ku + o.du;
        const int kv2 = kv + o.dv;
        if (ku2 < 0 || ku2 >= n || kv2 >= n)
          continue;
        const std::size_t a = index(ku, kv, n);
        const std::size_t b = index(ku2, kv2, n);
        const double rest = glm::length(particles_.get_position(a) - particles_.get_position(b));
        springs_[static_cast<int>(o.family)].push_back(
            {static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), rest});
      }
    }
  }

  // Question 7: the two corners (0, 0) and (N-1, 0) never move.
  if (parameters.pins == pin_mode::corners) {
    particles_.is_fixed[index(0, 0, n)] = 1;
    particles_.is_fixed[index(n - 1, 0, n)] = 1;
  }
  compute_normals();
}

void spring_mesh::compute_normals() {
  compute_vertex_normals(grid_size_, particles_.position, normals_);
}

void spring_mesh::compute_force() {
  // The springs of the three families, then the wind with the normals of the positions at the
  // start of the step (which it computes into normals(); nothing else in a step needs them).
  const std::array<spring_set, 3> sets = spring_sets();
  evaluate_forces(forces(sets), particles_.position, particles_.force);
}

void spring_mesh::apply_force() {
  // The mass (and stiffnesses) that the grid size implies in the chosen scaling (question 10).
  const cloth_parameters effective = effective_parameters();
  const std::array<spring_set, 3> sets = spring_sets();
  integrator_.step(effective.dynamics, forces(sets), particles_);
  if (parameters.ground_enabled) {
    apply_ground_contact(parameters.ground_height, parameters.ground_friction,
                         parameters.dynamics.time_step, particles_);
  }
}

void compute_vertex_normals(int n, std::span<const double> position, std::span<double> normal) {
  auto p = [&](int ku, int kv) {
    const std::size_t k = 3 * spring_mesh::index(ku, kv, n);
    return glm::dvec3(position[k], position[k + 1], position[k + 2]);
  };
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      // Central differences, one-sided on the border.
      const glm::dvec3 du = p(std::min(ku + 1, n - 1), kv) - p(std::max(ku - 1, 0), kv);
      const glm::dvec3 dv = p(ku, std::min(kv + 1, n - 1)) - p(ku, std::max(kv - 1, 0));
      const glm::dvec3 c = glm::cross(du, dv);
      const glm::dvec3 unit = c / glm::length(c);
      const std::size_t k = 3 * spring_mesh::index(ku, kv, n);
      normal[k] = unit.x;
      normal[k + 1] = unit.y;
      normal[k + 2] = unit.z;
    }
  }
}

void accumulate_wind_forces(double strength, const glm::dvec3& direction,
                            std::span<const double> normal, std::span<double> force) {
  const glm::dvec3 u = direction / glm::length(direction);  // u_w, unit
  const std::size_t count = normal.size() / 3;
  for (std::size_t k = 0; k < count; ++k) {
    const glm::dvec3 nk = {normal[3 * k], normal[3 * k + 1], normal[3 * k + 2]};
    const glm::dvec3 f = strength * glm::dot(nk, u) * nk;  // F_w = K_w <n, u_w> n
    force[3 * k] += f.x;
    force[3 * k + 1] += f.y;
    force[3 * k + 2] += f.z;
  }
}

void apply_ground_contact(double ground_height, double ground_friction, double time_step,
                          particle_system& particles) {
  const double friction_factor = 1.0 - ground_friction * time_step;  // (1 - mu_g dt)
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    double* p = &particles.position[3 * k];
    double* v = &particles.velocity[3 * k];
    if (p[2] < ground_height) {
      p[2] = ground_height;
      v[2] = std::max(v[2], 0.0);
      v[0] *= friction_factor;
      v[1] *= friction_factor;
    }
  }
}

}  // namespace clothlab
