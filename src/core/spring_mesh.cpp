#include "spring_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "contacts.hpp"
#include "integrator.hpp"

namespace clothlab {
namespace {

// The neighbours s(ku + du, kv + dv) that a spring joins to the vertex s(ku, kv), per family
// (handout, figure 6).
struct grid_offset {
  int du;
  int dv;
};
constexpr grid_offset structural_neighbours[] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
constexpr grid_offset shear_neighbours[] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
constexpr grid_offset bending_neighbours[] = {{2, 0}, {0, 2}, {-2, 0}, {0, -2}};

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
  return {sets, [this](std::span<const double> position, std::span<double> force) {
            compute_force(position, force);
          }};
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

  // Rest lengths are the distances in this initial configuration (h, h sqrt(2) and 2h, up to
  // rounding), kept for every vertex and every offset (du, dv) in [-2, 2]^2 that stays inside.
  const auto rest_distance = [&](std::size_t a, std::size_t b) {
    return glm::length(particles_.get_position(a) - particles_.get_position(b));
  };
  rest_lengths_.assign(rest_length_slot(particles_.size(), -2, -2), 0.0);
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      for (int dv = -2; dv <= 2; ++dv) {
        for (int du = -2; du <= 2; ++du) {
          if (ku + du >= 0 && ku + du < n && kv + dv >= 0 && kv + dv < n) {
            rest_lengths_[rest_length_slot(index(ku, kv, n), du, dv)] =
                rest_distance(index(ku, kv, n), index(ku + du, kv + dv, n));
          }
        }
      }
    }
  }
  rest_length_ = {rest_distance(index(0, 0, n), index(1, 0, n)),
                  rest_distance(index(0, 0, n), index(1, 1, n)),
                  n > 2 ? rest_distance(index(0, 0, n), index(2, 0, n)) : 2 * h};

  // The list of the springs, each once (drawing, energy, the implicit scheme's Jacobian).
  for (auto& family : springs_)
    family.clear();
  const auto add_springs = [&](spring_family family, std::span<const grid_offset> neighbours) {
    for (int kv = 0; kv < n; ++kv) {
      for (int ku = 0; ku < n; ++ku) {
        for (const grid_offset o : neighbours) {
          const int ku2 = ku + o.du;
          const int kv2 = kv + o.dv;
          const std::size_t a = index(ku, kv, n);
          if (ku2 < 0 || ku2 >= n || kv2 < 0 || kv2 >= n || index(ku2, kv2, n) < a)
            continue;  // outside the grid, or already listed from the other end
          const std::size_t b = index(ku2, kv2, n);
          springs_[static_cast<int>(family)].push_back(
              {static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), rest_distance(a, b)});
        }
      }
    }
  };
  add_springs(spring_family::structural, structural_neighbours);
  add_springs(spring_family::shear, shear_neighbours);
  add_springs(spring_family::bending, bending_neighbours);
  // Every spring is intact until it tears (tear_springs).
  spring_intact_.assign(rest_lengths_.size(), 0);
  for (const auto& family : springs_) {
    for (const spring& s : family)
      set_spring_intact(s, 1);
  }

  // Question 7: the two corners (0, 0) and (N-1, 0) never move.
  if (parameters.pins == pin_mode::corners) {
    // BEGIN SOLUTION Q7: pin two corners
    // STUDENT| // TODO Q7 (pins): fix the two corners s(0, 0) and s(N-1, 0): set
    // STUDENT| // particles_.is_fixed[k] = 1 for their index k = index(ku, kv, n). apply_force
    // STUDENT| // never moves a fixed vertex. For now nothing is pinned: the cloth falls whole.
    particles_.is_fixed[index(0, 0, n)] = 1;
    particles_.is_fixed[index(n - 1, 0, n)] = 1;
    // END SOLUTION Q7
  }
  compute_normals();
}

void spring_mesh::compute_normals() {
  compute_vertex_normals(grid_size_, particles_.position, normals_);
}

void spring_mesh::compute_force() {
  compute_force(particles_.position, particles_.force);
}

void spring_mesh::compute_force(std::span<const double> position, std::span<double> force) {
  const int N = grid_size_;
  // The stiffnesses the simulation uses at this N (question 10; the sliders' values by default).
  // [[maybe_unused]]: the TODO stubs of the student copy do not use them yet.
  const cloth_parameters used = effective_parameters();
  [[maybe_unused]] const double K_structural = used.structural_stiffness;  // N/m
  [[maybe_unused]] const double K_shear = used.shear_stiffness;
  [[maybe_unused]] const double K_bending = used.bending_stiffness;

  // x(ku, kv): the position of the vertex s(ku, kv), at 3 (ku + N kv) of the flat array.
  const auto x = [position, N](int ku, int kv) {
    const std::size_t u = 3 * index(ku, kv, N);
    return glm::dvec3(position[u], position[u + 1], position[u + 2]);
  };
  // L0(ku, kv, du, dv): the rest length of the spring from s(ku, kv) to s(ku + du, kv + dv), their
  // distance in the initial configuration (h, h sqrt 2 or 2h).
  [[maybe_unused]] const auto L0 = [this, N](int ku, int kv, int du, int dv) {
    return rest_lengths_[rest_length_slot(index(ku, kv, N), du, dv)];
  };
  // joined(ku, kv, du, dv): a spring joins s(ku, kv) to s(ku + du, kv + dv): the neighbour is
  // inside the grid (springs stop at its border) and the spring is not torn (tearing is an
  // addition of clothlab, off by default).
  [[maybe_unused]] const auto joined = [this, N](int ku, int kv, int du, int dv) {
    return ku + du >= 0 && ku + du < N && kv + dv >= 0 && kv + dv < N &&
           spring_intact_[rest_length_slot(index(ku, kv, N), du, dv)] != 0;
  };

  // The wind (question 13) needs the normals of these positions: into normals() at the
  // current state, into a scratch array at an integrator's intermediate state.
  const double K_w = used.wind_strength;  // N
  [[maybe_unused]] const glm::dvec3 u_w =
      used.wind_direction / glm::length(used.wind_direction);  // unit
  const bool current_state = position.data() == particles_.position.data();
  std::vector<double>& normal = current_state ? normals_ : stage_normals_;
  if (K_w != 0.0) {
    normal.resize(position.size());
    compute_vertex_normals(N, position, normal);
  }
  // n(ku, kv): the unit normal at s(ku, kv) (only when there is wind).
  [[maybe_unused]] const auto n = [&normal, N](int ku, int kv) {
    const std::size_t u = 3 * index(ku, kv, N);
    return glm::dvec3(normal[u], normal[u + 1], normal[u + 2]);
  };

  for (int kv = 0; kv < N; ++kv) {
    for (int ku = 0; ku < N; ++ku) {
      [[maybe_unused]] const glm::dvec3 x_current = x(ku, kv);
      glm::dvec3 f = {0.0, 0.0, 0.0};  // the force on s(ku, kv), N (gravity: in apply_force)

      // BEGIN SOLUTION Q8: structural springs
      // STUDENT| // TODO Q8 (structural springs): for each neighbour (du, dv) in
      // STUDENT| // structural_neighbours, s(ku+1, kv), s(ku, kv+1), s(ku-1, kv), s(ku, kv-1), that
      // STUDENT| // is joined(ku, kv, du, dv) to s(ku, kv), add the force of equation 2 of the spring
      // STUDENT| // from x_current to x(ku + du, kv + dv), of stiffness K_structural and rest length
      // STUDENT| // L0(ku, kv, du, dv):  f += spring_force(x_current, x_neighbour, K, rest_length).
      for (const auto [du, dv] : structural_neighbours) {
        if (joined(ku, kv, du, dv))
          f += spring_force(x_current, x(ku + du, kv + dv), K_structural, L0(ku, kv, du, dv));
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: shear springs
      // STUDENT| // TODO Q8 (shear springs): the same with shear_neighbours, the four diagonals
      // STUDENT| // s(ku+1, kv+1), s(ku-1, kv+1), s(ku-1, kv-1), s(ku+1, kv-1), and K_shear.
      for (const auto [du, dv] : shear_neighbours) {
        if (joined(ku, kv, du, dv))
          f += spring_force(x_current, x(ku + du, kv + dv), K_shear, L0(ku, kv, du, dv));
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: bending springs
      // STUDENT| // TODO Q8 (bending springs): the same with bending_neighbours, two vertices away,
      // STUDENT| // s(ku+2, kv), s(ku, kv+2), s(ku-2, kv), s(ku, kv-2), and K_bending.
      for (const auto [du, dv] : bending_neighbours) {
        if (joined(ku, kv, du, dv))
          f += spring_force(x_current, x(ku + du, kv + dv), K_bending, L0(ku, kv, du, dv));
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q13: wind
      // STUDENT| // TODO Q13 (wind): when K_w != 0, add F_w = K_w <n, u_w> n, with n(ku, kv)
      // STUDENT| // the unit normal at the vertex and u_w the unit wind direction (glm::dot).
      const glm::dvec3 normal_here = K_w != 0.0 ? n(ku, kv) : glm::dvec3(0.0);  // no wind: none
      f += K_w * glm::dot(normal_here, u_w) * normal_here;
      // END SOLUTION Q13

      const std::size_t u = 3 * index(ku, kv, N);
      force[u] = f.x;
      force[u + 1] = f.y;
      force[u + 2] = f.z;
    }
  }

  // The mouse drag (an addition, docs/model.md): F_d = K_d (q - p) on the dragged particle,
  // unless it is pinned.
  const drag_parameters& drag = used.drag;
  if (drag.enabled && drag.ku >= 0 && drag.ku < N && drag.kv >= 0 && drag.kv < N) {
    const std::size_t k = index(drag.ku, drag.kv, N);
    if (!particles_.is_fixed[k]) {
      const glm::dvec3 pull = drag.stiffness * (drag.target - x(drag.ku, drag.kv));
      for (int c = 0; c < 3; ++c)
        force[3 * k + static_cast<std::size_t>(c)] += pull[c];
    }
  }
}

void spring_mesh::apply_force() {
  // The mass (and stiffnesses) that the grid size implies in the chosen scaling (question 10).
  const cloth_parameters used = effective_parameters();
  const dynamics_parameters& d = used.dynamics;
  if (d.integrator == integrator_kind::semi_implicit) {
    // The handout's explicit Euler (section 4.3): the velocities first, then the positions with
    // the new velocities.
    const double dt = d.time_step;                // s
    const glm::dvec3 g = {0.0, 0.0, -d.gravity};  // m/s^2
    const std::size_t count = particles_.size();
    // BEGIN SOLUTION Q6: apply_force, the handout's two loops
    // STUDENT| // TODO Q6 (apply_force): for every vertex k that is not fixed (is_fixed[k] == 0),
    // STUDENT| //   speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g)
    // STUDENT| // with mu = d.damping (1/s) and m = d.mass (kg); then, in a second loop,
    // STUDENT| //   vertices[k] += dt speed[k].
    // STUDENT| // Use particles_.get_force(k), get_velocity(k), set_velocity(k, v), get_position(k)
    // STUDENT| // and set_position(k, p). For now every vertex falls freely: no springs, no damping.
    // STUDENT| for (std::size_t k = 0; k < count; ++k) {
    // STUDENT|   if (particles_.is_fixed[k])
    // STUDENT|     continue;
    // STUDENT|   const glm::dvec3 v = particles_.get_velocity(k) + dt * g;
    // STUDENT|   particles_.set_velocity(k, v);
    // STUDENT|   particles_.set_position(k, particles_.get_position(k) + dt * v);
    // STUDENT| }
    const double mu = d.damping;  // 1/s
    const double m = d.mass;      // kg
    // for every vertex k: speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g)
    for (std::size_t k = 0; k < count; ++k) {
      if (particles_.is_fixed[k])
        continue;  // a fixed vertex never moves (question 7)
      const glm::dvec3 acceleration = particles_.get_force(k) / m + g;
      particles_.set_velocity(k, (1.0 - dt * mu) * particles_.get_velocity(k) + dt * acceleration);
    }
    // for every vertex k: vertices[k] += dt speed[k]
    for (std::size_t k = 0; k < count; ++k) {
      if (particles_.is_fixed[k])
        continue;
      const glm::dvec3 new_position = particles_.get_position(k) + dt * particles_.get_velocity(k);
      particles_.set_position(k, new_position);
    }
    // END SOLUTION Q6
  } else {
    // The stability lab's other schemes (src/core/integrator.cpp), not a question of the lab.
    integrator_.step(d, forces(spring_sets()), particles_);
  }
  // The contacts, in the order of docs/model.md: the sphere (an addition), the ground
  // (question 9), self-collision (an addition), then tearing (an addition).
  if (parameters.sphere.enabled)
    apply_sphere_contact(parameters.sphere, d.time_step, particles_);
  if (parameters.ground_enabled) {  // question 9
    apply_ground_contact(parameters.ground_height, parameters.ground_friction, d.time_step,
                         particles_);
  }
  if (parameters.self_collision_thickness > 0.0)
    self_collision_.apply(grid_size_, self_collision_distance(parameters), particles_);
  if (parameters.tear_strain > 0.0)
    tear_springs(parameters.tear_strain);
}

std::size_t spring_mesh::tear_springs(double strain) {
  return remove_springs([&](spring_family, const spring& s) {
    const double length = glm::length(particles_.get_position(s.a) - particles_.get_position(s.b));
    return length > (1.0 + strain) * s.rest_length;
  });
}

void spring_mesh::set_spring_intact(const spring& s, std::uint8_t intact) {
  const int n = grid_size_;
  const int du = static_cast<int>(s.b % n) - static_cast<int>(s.a % n);
  const int dv = static_cast<int>(s.b / n) - static_cast<int>(s.a / n);
  spring_intact_[rest_length_slot(s.a, du, dv)] = intact;
  spring_intact_[rest_length_slot(s.b, -du, -dv)] = intact;
}

bool spring_mesh::triangle_intact(int ku, int kv, bool upper) const {
  const int n = grid_size_;
  const std::size_t k = index(ku, kv, n);
  // Lower (ku, kv), (ku+1, kv), (ku+1, kv+1); upper (ku, kv), (ku+1, kv+1), (ku, kv+1): both
  // share the shear diagonal (ku, kv)-(ku+1, kv+1).
  const bool diagonal = spring_intact_[rest_length_slot(k, 1, 1)] != 0;
  if (upper) {
    return diagonal && spring_intact_[rest_length_slot(k, 0, 1)] != 0 &&
           spring_intact_[rest_length_slot(index(ku, kv + 1, n), 1, 0)] != 0;
  }
  return diagonal && spring_intact_[rest_length_slot(k, 1, 0)] != 0 &&
         spring_intact_[rest_length_slot(index(ku + 1, kv, n), 0, 1)] != 0;
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

void apply_ground_contact(double ground_height, double ground_friction, double time_step,
                          particle_system& particles) {
  // [[maybe_unused]]: the TODO stub of the student copy does not use them yet.
  [[maybe_unused]] const double z_g = ground_height;     // m
  [[maybe_unused]] const double mu_g = ground_friction;  // 1/s
  [[maybe_unused]] const double dt = time_step;          // s
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (particles.is_fixed[k])
      continue;
    glm::dvec3 p = particles.get_position(k);
    glm::dvec3 v = particles.get_velocity(k);
    // BEGIN SOLUTION Q9: the ground z = z_g
    // STUDENT| // TODO Q9 (ground): if the vertex is below the plane (p.z < z_g), put it back on it
    // STUDENT| // (p.z = z_g), stop its fall (v.z = max(v.z, 0)) and damp its sliding by fluid
    // STUDENT| // friction: (v.x, v.y) *= (1 - mu_g dt). For now the cloth falls through the floor.
    if (p.z < z_g) {
      p.z = z_g;
      v.z = std::max(v.z, 0.0);
      v.x *= 1.0 - mu_g * dt;
      v.y *= 1.0 - mu_g * dt;
    }
    // END SOLUTION Q9
    particles.set_position(k, p);
    particles.set_velocity(k, v);
  }
}

}  // namespace clothlab
