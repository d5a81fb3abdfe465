#include "core/spring_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/contacts.hpp"
#include "core/grid_neighbours.hpp"  // structural_neighbours, ... (handout, figure 6)
#include "core/integrator.hpp"

namespace clothlab {

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
  spacing_ = h;
  particles_.resize(static_cast<std::size_t>(n) * n);
  normals_.assign(3 * particles_.size(), 0.0);

  // Flat, at rest: p(ku, kv) = (-S/2 + ku h, -S/2 + kv h, 0).
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      particles_.set_position(index(ku, kv, n), {-side / 2 + ku * h, -side / 2 + kv * h, 0.0});
    }
  }

  // The initial positions x0: rest lengths are the distances in this configuration.
  rest_position_ = particles_.position;
  const auto rest_distance = [&](std::size_t a, std::size_t b) {
    return glm::length(particles_.get_position(a) - particles_.get_position(b));
  };

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
  spring_torn_.assign(spring_slot(particles_.size(), -2, -2), 0);

  // Question 7: the two corners (0, 0) and (N-1, 0) never move.
  if (parameters.pins == pin_mode::corners) {
    // BEGIN SOLUTION Q7: pin two corners
    // STUDENT(handout)| // TODO Q7 (pins): fix two corners of the cloth, s(0, 0) and s(N-1, 0)
    // STUDENT(handout)| // (n here): apply_force never moves a vertex marked in particles_.is_fixed
    // STUDENT(handout)| // (index(ku, kv, n) gives its index k). For now nothing is pinned: the cloth
    // STUDENT(handout)| // falls whole. Done when ./test.sh -L q7 passes.
    // STUDENT(guided)| // TODO Q7 (pins): fix the two corners s(0, 0) and s(N-1, 0): set
    // STUDENT(guided)| // particles_.is_fixed[k] = 1 for their index k = index(ku, kv, n). apply_force
    // STUDENT(guided)| // never moves a fixed vertex. For now nothing is pinned: the cloth falls whole.
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
  // x0(ku, kv): the position of s(ku, kv) in the initial flat cloth, at rest (load_model), and
  // h, the distance between two neighbours of a row there, m.
  [[maybe_unused]] const auto x0 = [this, N](int ku, int kv) {
    const std::size_t u = 3 * index(ku, kv, N);
    return glm::dvec3(rest_position_[u], rest_position_[u + 1], rest_position_[u + 2]);
  };
  [[maybe_unused]] const double h = spacing_;

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
      // STUDENT(handout)| // TODO Q8 (structural springs): add to f the forces of the structural
      // STUDENT(handout)| // springs that join s(ku, kv) to its neighbours (section 4.4 of the handout,
      // STUDENT(handout)| // figure 6; structural_neighbours lists their offsets (du, dv)). A spring
      // STUDENT(handout)| // pulls by equation 2 (spring_force) with stiffness K_structural and its
      // STUDENT(handout)| // rest length L0: derive L0 from the initial flat cloth (h, the grid
      // STUDENT(handout)| // spacing, and x0(ku, kv), the initial positions, are at hand). Decide
      // STUDENT(handout)| // which springs exist at the border of the N x N grid, and leave out a
      // STUDENT(handout)| // spring that tore: spring_intact(ku, kv, du, dv), for a neighbour inside
      // STUDENT(handout)| // the grid. Done when ./test.sh -L q8 passes and the cloth hangs together.
      // STUDENT(guided)| // TODO Q8 (structural springs): for each (du, dv) in structural_neighbours,
      // STUDENT(guided)| // the neighbour s(ku + du, kv + dv) = s(ku+1, kv), s(ku, kv+1), s(ku-1, kv),
      // STUDENT(guided)| // s(ku, kv-1): if it is inside the grid (0 <= ku + du < N, 0 <= kv + dv < N)
      // STUDENT(guided)| // and spring_intact(ku, kv, du, dv) (not torn), add the force of equation 2,
      // STUDENT(guided)| //   f += spring_force(x_current, x(ku + du, kv + dv), K_structural, L0),
      // STUDENT(guided)| // L0 the rest length: h for a structural spring (h sqrt 2 for a shear one,
      // STUDENT(guided)| // 2h for a bending one; or the distance of x0 of the two vertices).
      for (const auto [du, dv] : structural_neighbours) {
        const int ku2 = ku + du;  // the neighbour s(ku2, kv2)
        const int kv2 = kv + dv;
        if (ku2 < 0 || ku2 >= N || kv2 < 0 || kv2 >= N || !spring_intact(ku, kv, du, dv))
          continue;  // no spring past the border of the grid; a torn spring pulls no more
        const double L0 = glm::length(x0(ku, kv) - x0(ku2, kv2));  // its length at rest
        f += spring_force(x_current, x(ku2, kv2), K_structural, L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: shear springs
      // STUDENT(handout)| // TODO Q8 (shear springs): the same for the shear springs
      // STUDENT(handout)| // (shear_neighbours, stiffness K_shear): their rest length is yours to
      // STUDENT(handout)| // derive too.
      // STUDENT(guided)| // TODO Q8 (shear springs): the same with shear_neighbours, the four
      // STUDENT(guided)| // diagonals s(ku+1, kv+1), s(ku-1, kv+1), s(ku-1, kv-1), s(ku+1, kv-1),
      // STUDENT(guided)| // K_shear and L0 = h sqrt 2.
      for (const auto [du, dv] : shear_neighbours) {
        const int ku2 = ku + du;
        const int kv2 = kv + dv;
        if (ku2 < 0 || ku2 >= N || kv2 < 0 || kv2 >= N || !spring_intact(ku, kv, du, dv))
          continue;
        const double L0 = glm::length(x0(ku, kv) - x0(ku2, kv2));
        f += spring_force(x_current, x(ku2, kv2), K_shear, L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: bending springs
      // STUDENT(handout)| // TODO Q8 (bending springs): the same for the bending springs, two
      // STUDENT(handout)| // vertices away (bending_neighbours, stiffness K_bending).
      // STUDENT(guided)| // TODO Q8 (bending springs): the same with bending_neighbours, two vertices
      // STUDENT(guided)| // away, s(ku+2, kv), s(ku, kv+2), s(ku-2, kv), s(ku, kv-2), K_bending and
      // STUDENT(guided)| // L0 = 2h.
      for (const auto [du, dv] : bending_neighbours) {
        const int ku2 = ku + du;
        const int kv2 = kv + dv;
        if (ku2 < 0 || ku2 >= N || kv2 < 0 || kv2 >= N || !spring_intact(ku, kv, du, dv))
          continue;
        const double L0 = glm::length(x0(ku, kv) - x0(ku2, kv2));
        f += spring_force(x_current, x(ku2, kv2), K_bending, L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q13: wind
      // STUDENT(handout)| // TODO Q13 (wind): add the force of the wind on the vertex, the handout's
      // STUDENT(handout)| // F_w = K_w <n, u_w> n (section 5), K_w the wind's strength, u_w its unit
      // STUDENT(handout)| // direction, n(ku, kv) the unit normal at the vertex (only valid when K_w
      // STUDENT(handout)| // != 0). Done when ./test.sh -L q13 passes and the cloth billows.
      // STUDENT(guided)| // TODO Q13 (wind): when K_w != 0, add F_w = K_w <n, u_w> n, with n(ku, kv)
      // STUDENT(guided)| // the unit normal at the vertex and u_w the unit wind direction (glm::dot).
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
  if (d.integrator == integrator_kind::semi_implicit ||
      d.integrator == integrator_kind::explicit_euler) {
    // Question 6, the handout's explicit Euler (section 4.3). semi_implicit (the default) is the
    // handout's code order; explicit_euler is its equation 6 taken literally.
    [[maybe_unused]] const bool handout_order = d.integrator == integrator_kind::semi_implicit;
    const double dt = d.time_step;                 // s
    const glm::dvec3 g = {0.0, 0.0, -d.gravity};   // m/s^2
    [[maybe_unused]] const double mu = d.damping;  // 1/s
    [[maybe_unused]] const double m = d.mass;      // kg
    const std::size_t count = particles_.size();
    // BEGIN SOLUTION Q6: apply_force, the handout's two loops
    // STUDENT(handout)| // TODO Q6 (apply_force): integrate the vertices over one step dt by the
    // STUDENT(handout)| // handout's explicit Euler: its pseudo-code of section 4.3 (the two loops
    // STUDENT(handout)| // over the vertices, handout_order) and, for --integrator explicit, its
    // STUDENT(handout)| // equation 6 taken literally (both updates from the state at the start of
    // STUDENT(handout)| // the step). The acceleration is the force over the mass m plus gravity g
    // STUDENT(handout)| // (equation 4), with damping mu. A fixed vertex never moves. At hand:
    // STUDENT(handout)| // particles_.get_force(k), get_velocity(k), set_velocity(k, v),
    // STUDENT(handout)| // get_position(k), set_position(k, p), is_fixed[k]. For now every vertex
    // STUDENT(handout)| // falls freely. Done when ./test.sh -L q6 passes.
    // STUDENT(guided)| // TODO Q6 (apply_force): for every vertex k that is not fixed
    // STUDENT(guided)| // (is_fixed[k] == 0),
    // STUDENT(guided)| //   speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g)
    // STUDENT(guided)| // then, in a second loop, vertices[k] += dt speed[k] (handout_order); for
    // STUDENT(guided)| // --integrator explicit, one loop with the position moved by the OLD speed.
    // STUDENT(guided)| // Use particles_.get_force(k), get_velocity(k), set_velocity(k, v),
    // STUDENT(guided)| // get_position(k) and set_position(k, p). For now every vertex falls freely.
    // STUDENT| for (std::size_t k = 0; k < count; ++k) {
    // STUDENT|   if (particles_.is_fixed[k])
    // STUDENT|     continue;
    // STUDENT|   const glm::dvec3 v = particles_.get_velocity(k) + dt * g;
    // STUDENT|   particles_.set_velocity(k, v);
    // STUDENT|   particles_.set_position(k, particles_.get_position(k) + dt * v);
    // STUDENT| }
    if (handout_order) {
      // for every vertex k: speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g)
      for (std::size_t k = 0; k < count; ++k) {
        if (particles_.is_fixed[k])
          continue;  // a fixed vertex never moves (question 7)
        const glm::dvec3 acceleration = particles_.get_force(k) / m + g;
        particles_.set_velocity(k,
                                (1.0 - dt * mu) * particles_.get_velocity(k) + dt * acceleration);
      }
      // for every vertex k: vertices[k] += dt speed[k]
      for (std::size_t k = 0; k < count; ++k) {
        if (particles_.is_fixed[k])
          continue;
        particles_.set_position(k, particles_.get_position(k) + dt * particles_.get_velocity(k));
      }
    } else {
      // Equation 6: p(t + dt) = p(t) + dt v(t), v(t + dt) = (1 - mu dt) v(t) + dt (F / m + g).
      for (std::size_t k = 0; k < count; ++k) {
        if (particles_.is_fixed[k])
          continue;
        const glm::dvec3 v = particles_.get_velocity(k);
        particles_.set_position(k, particles_.get_position(k) + dt * v);
        particles_.set_velocity(k, (1.0 - dt * mu) * v + dt * (particles_.get_force(k) / m + g));
      }
    }
    // END SOLUTION Q6
  } else {
    // The stability lab's other schemes (src/core/integrator.cpp), not a question of the lab.
    integrator_.step(d, forces(spring_sets()), particles_);
  }
}

void spring_mesh::apply_constraints() {
  // In the order of docs/model.md: the sphere (an addition), the ground (question 9),
  // self-collision (an addition), then tearing (an addition). The pins are apply_force's: it
  // never moves a fixed vertex.
  const double dt = effective_parameters().dynamics.time_step;
  if (parameters.sphere.enabled)
    apply_sphere_contact(parameters.sphere, dt, particles_);
  if (parameters.ground_enabled)  // question 9
    apply_ground_contact(parameters.ground_height, parameters.ground_friction, dt, particles_);
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

void spring_mesh::set_spring_torn(const spring& s) {
  const int n = grid_size_;
  const int du = static_cast<int>(s.b % n) - static_cast<int>(s.a % n);
  const int dv = static_cast<int>(s.b / n) - static_cast<int>(s.a / n);
  spring_torn_[spring_slot(s.a, du, dv)] = 1;
  spring_torn_[spring_slot(s.b, -du, -dv)] = 1;
}

void spring_mesh::throw_not_a_neighbour(int ku, int kv, int du, int dv) const {
  const int n = grid_size_;
  throw std::out_of_range("spring_intact(" + std::to_string(ku) + ", " + std::to_string(kv) + ", " +
                          std::to_string(du) + ", " + std::to_string(dv) + "): s(" +
                          std::to_string(ku + du) + ", " + std::to_string(kv + dv) +
                          ") is not a neighbour inside the " + std::to_string(n) + " x " +
                          std::to_string(n) + " grid: no spring can join it to s(" +
                          std::to_string(ku) + ", " + std::to_string(kv) + ")");
}

bool spring_mesh::triangle_intact(int ku, int kv, bool upper) const {
  const int n = grid_size_;
  const std::size_t k = index(ku, kv, n);
  // Lower (ku, kv), (ku+1, kv), (ku+1, kv+1); upper (ku, kv), (ku+1, kv+1), (ku, kv+1): both
  // share the shear diagonal (ku, kv)-(ku+1, kv+1).
  const auto intact = [this](std::size_t a, int du, int dv) {
    return spring_torn_[spring_slot(a, du, dv)] == 0;
  };
  const bool diagonal = intact(k, 1, 1);
  if (upper)
    return diagonal && intact(k, 0, 1) && intact(index(ku, kv + 1, n), 1, 0);
  return diagonal && intact(k, 1, 0) && intact(index(ku + 1, kv, n), 0, 1);
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
    // STUDENT(handout)| // TODO Q9 (ground): model the plane z = z_g (handout question 9): a vertex
    // STUDENT(handout)| // may not stay below it, and a vertex in contact with it is slowed by a
    // STUDENT(handout)| // fluid friction of rate mu_g (like the damping of equation 3, along the
    // STUDENT(handout)| // plane). p and v are the vertex's position and velocity after the
    // STUDENT(handout)| // integration, dt the step: decide what becomes of the position and of each
    // STUDENT(handout)| // component of the velocity. For now the cloth falls through the floor.
    // STUDENT(handout)| // Done when ./test.sh -L q9 passes and the cloth lies on the checkerboard.
    // STUDENT(guided)| // TODO Q9 (ground): if the vertex is below the plane (p.z < z_g), put it back
    // STUDENT(guided)| // on it (p.z = z_g), stop its fall (v.z = max(v.z, 0)) and damp its sliding by
    // STUDENT(guided)| // fluid friction: (v.x, v.y) *= (1 - mu_g dt). For now the cloth falls
    // STUDENT(guided)| // through the floor.
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
