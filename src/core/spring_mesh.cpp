// The handout's spring_mesh (section 4): what a student reads and writes for questions 6 to 9
// and 13, in the handout's order: apply_force (6), the pins in load_model (7), compute_force (8,
// and the wind of 13), the ground (9). What the rest of clothlab needs from the cloth is beside it:
// spring_mesh_step.cpp (the mouse drag, the stability lab's schemes, the constraints),
// spring_mesh_geometry.cpp (the springs' list, the normals) and tearing.cpp.
#include "core/spring_mesh.hpp"

#include <algorithm>

#include "core/grid_neighbours.hpp"  // structural_neighbours, ... (handout, figure 6)

namespace clothlab {

spring_mesh::spring_mesh(const cloth_parameters& p) : parameters(p) {
  load_model();
}

void spring_mesh::apply_force() {
  // dt, the damping mu, the mass m (at this N: question 10) and g0, the handout's 9.8 m/s^2.
  const dynamics_parameters d = effective_parameters().dynamics;
  std::span<glm::dvec3> vertices = as_vectors(particles_.position);   // m
  std::span<glm::dvec3> speed = as_vectors(particles_.velocity);      // m/s
  std::span<const glm::dvec3> forces = as_vectors(particles_.force);  // N, from compute_force
  // BEGIN SOLUTION Q6: apply_force, the handout's two loops
  // STUDENT(handout)| // TODO Q6 (apply_force): integrate the vertices over one step dt by the
  // STUDENT(handout)| // handout's explicit Euler in its code order: the pseudo-code of section 4.3
  // STUDENT(handout)| // (its two loops over the vertices). The acceleration is the force over the
  // STUDENT(handout)| // mass m = d.mass plus gravity g = (0, 0, -d.gravity) (equation 4), with the
  // STUDENT(handout)| // damping mu = d.damping and dt = d.time_step. A fixed vertex
  // STUDENT(handout)| // (particles_.is_fixed[k]) never moves: the pins, the mouse and the GPU path
  // STUDENT(handout)| // count on it. (--integrator explicit, equation 6 taken literally, is built on
  // STUDENT(handout)| // this function: nothing to write for it.) For now every vertex falls freely.
  // STUDENT(handout)| // Done when ./test.sh -L q6 passes.
  // STUDENT(guided)| // TODO Q6 (apply_force): with dt = d.time_step, mu = d.damping, m = d.mass and
  // STUDENT(guided)| // g = (0, 0, -d.gravity), for every vertex k that is not fixed
  // STUDENT(guided)| // (particles_.is_fixed[k] == 0),
  // STUDENT(guided)| //   speed[k] = (1 - dt mu) speed[k] + dt (forces[k] / m + g)
  // STUDENT(guided)| // then, in a second loop, vertices[k] += dt speed[k]. (--integrator explicit
  // STUDENT(guided)| // is built on this function.) For now every vertex falls freely.
  // STUDENT| const double dt = d.time_step;
  // STUDENT| const glm::dvec3 g = {0.0, 0.0, -d.gravity};
  // STUDENT| for (std::size_t k = 0; k < vertices.size(); ++k) {
  // STUDENT|   if (!particles_.is_fixed[k]) {
  // STUDENT|     speed[k] += dt * g;
  // STUDENT|     vertices[k] += dt * speed[k];
  // STUDENT|   }
  // STUDENT| }
  const double dt = d.time_step;                // s
  const double mu = d.damping;                  // 1/s
  const double m = d.mass;                      // kg
  const glm::dvec3 g = {0.0, 0.0, -d.gravity};  // m/s^2
  // The handout's pseudo-code (section 4.3), a fixed vertex left as it is (question 7).
  for (std::size_t k = 0; k < vertices.size(); ++k)
    if (!particles_.is_fixed[k])
      speed[k] = (1 - dt * mu) * speed[k] + dt * (forces[k] / m + g);
  for (std::size_t k = 0; k < vertices.size(); ++k)
    if (!particles_.is_fixed[k])
      vertices[k] += dt * speed[k];
  // END SOLUTION Q6
}

void spring_mesh::load_model() {
  const int n = std::max(parameters.grid_size, 2);
  const double side = parameters.side_length;
  grid_size_ = n;
  spacing_ = side / (n - 1);  // h, the rest distance between grid neighbours
  particles_.resize(static_cast<std::size_t>(n) * n);  // at rest, none fixed

  // Flat, at rest: s(ku, kv) at (-S/2 + ku h, -S/2 + kv h, 0).
  std::span<glm::dvec3> vertices = as_vectors(particles_.position);
  for (int kv = 0; kv < n; ++kv)
    for (int ku = 0; ku < n; ++ku)
      vertices[index(ku, kv, n)] = {-side / 2 + ku * spacing_, -side / 2 + kv * spacing_, 0.0};
  rest_position_ = particles_.position;  // x0: the rest lengths are its distances

  list_springs();  // the springs of figure 6, for drawing, the energy and tearing

  // Question 7: two corners of the cloth never move (with --pins corners, the default).
  if (parameters.pins == pin_mode::corners) {
    // BEGIN SOLUTION Q7: pin two corners
    // STUDENT(handout)| // TODO Q7 (pins): fix two corners of the cloth (handout question 7; the
    // STUDENT(handout)| // corners are s(0, 0), s(N-1, 0), s(0, N-1) and s(N-1, N-1), N = n here, and
    // STUDENT(handout)| // index(ku, kv, n) gives the index k of s(ku, kv)). apply_force never moves
    // STUDENT(handout)| // a vertex marked in particles_.is_fixed; or, as the handout's section 4.3
    // STUDENT(handout)| // suggests, apply_force may skip the pinned vertices itself (then only when
    // STUDENT(handout)| // parameters.pins == pin_mode::corners: --pins none pins nothing). The
    // STUDENT(handout)| // pictures of the documents hang the cloth from s(0, 0) and s(N-1, 0). For
    // STUDENT(handout)| // now nothing is pinned: the cloth falls whole. Done when ./test.sh -L q7
    // STUDENT(handout)| // passes.
    // STUDENT(guided)| // TODO Q7 (pins): fix the two corners s(0, 0) and s(N-1, 0): set
    // STUDENT(guided)| // particles_.is_fixed[k] = 1 for their index k = index(ku, kv, n). apply_force
    // STUDENT(guided)| // never moves a fixed vertex. For now nothing is pinned: the cloth falls whole.
    particles_.is_fixed[index(0, 0, n)] = 1;
    particles_.is_fixed[index(n - 1, 0, n)] = 1;
    // END SOLUTION Q7
  }
  compute_normals();
  find_pins_and_gravity();  // wherever questions 6 to 8 put them (spring_mesh_step.cpp)
}

void spring_mesh::compute_force() {
  const int N = grid_size_;
  std::span<const glm::dvec3> vertices = as_vectors(particles_.position);  // m
  std::span<const glm::dvec3> initial = as_vectors(rest_position_);        // the flat cloth at rest
  std::span<glm::dvec3> forces = as_vectors(particles_.force);             // N
  if (parameters.wind_strength != 0.0)
    compute_normals();  // of the current positions, for the wind (question 13)
  std::span<const glm::dvec3> normals = as_vectors(normals_);  // unit

  for (int kv = 0; kv < N; ++kv) {
    for (int ku = 0; ku < N; ++ku) {
      const std::size_t k = index(ku, kv, N);
      glm::dvec3 f = {0.0, 0.0, 0.0};  // the force on s(ku, kv), N

      // BEGIN SOLUTION Q8: structural springs
      // STUDENT(handout)| // TODO Q8 (structural springs): add to f the forces of the structural
      // STUDENT(handout)| // springs of s(ku, kv) (section 4.4 of the handout, figure 6;
      // STUDENT(handout)| // structural_neighbours lists the offsets (du, dv) of its neighbours). A
      // STUDENT(handout)| // spring pulls by equation 2, spring_force(p_i, p_j, K, L0), with
      // STUDENT(handout)| // K = structural_stiffness() and its rest length L0: derive L0 from the
      // STUDENT(handout)| // flat cloth at rest (initial[k], the initial positions, and spacing(), h,
      // STUDENT(handout)| // are at hand). spring_intact(ku, kv, du, dv) says whether a spring joins
      // STUDENT(handout)| // s(ku, kv) to s(ku + du, kv + dv): not past the border of the grid, nor
      // STUDENT(handout)| // once it tore (clothlab's tearing, an addition off by default, removes a
      // STUDENT(handout)| // spring only through it). Done when ./test.sh -L q8 passes and the cloth
      // STUDENT(handout)| // hangs.
      // STUDENT(guided)| // TODO Q8 (structural springs): for each (du, dv) in structural_neighbours
      // STUDENT(guided)| // (s(ku+1, kv), s(ku, kv+1), s(ku-1, kv), s(ku, kv-1)) with
      // STUDENT(guided)| // spring_intact(ku, kv, du, dv) (inside the grid, not torn), the neighbour
      // STUDENT(guided)| // is k2 = index(ku + du, kv + dv, N): add the force of equation 2,
      // STUDENT(guided)| //   f += spring_force(vertices[k], vertices[k2], structural_stiffness(), L0),
      // STUDENT(guided)| // L0 the rest length: h = spacing() for a structural spring (h sqrt 2 for a
      // STUDENT(guided)| // shear one, 2h for a bending one; or glm::length(initial[k] - initial[k2])).
      for (const auto [du, dv] : structural_neighbours) {
        if (!spring_intact(ku, kv, du, dv))
          continue;  // past the border of the grid, or torn: no spring
        const std::size_t k2 = index(ku + du, kv + dv, N);        // the neighbour
        const double L0 = glm::length(initial[k] - initial[k2]);  // its length at rest
        f += spring_force(vertices[k], vertices[k2], structural_stiffness(), L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: shear springs
      // STUDENT(handout)| // TODO Q8 (shear springs): the same for the shear springs
      // STUDENT(handout)| // (shear_neighbours, K = shear_stiffness()): their rest length is yours to
      // STUDENT(handout)| // derive too.
      // STUDENT(guided)| // TODO Q8 (shear springs): the same with shear_neighbours, the four
      // STUDENT(guided)| // diagonals s(ku+1, kv+1), s(ku-1, kv+1), s(ku-1, kv-1), s(ku+1, kv-1),
      // STUDENT(guided)| // K = shear_stiffness() and L0 = h sqrt 2.
      for (const auto [du, dv] : shear_neighbours) {
        if (!spring_intact(ku, kv, du, dv))
          continue;
        const std::size_t k2 = index(ku + du, kv + dv, N);
        const double L0 = glm::length(initial[k] - initial[k2]);
        f += spring_force(vertices[k], vertices[k2], shear_stiffness(), L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q8: bending springs
      // STUDENT(handout)| // TODO Q8 (bending springs): the same for the bending springs, two
      // STUDENT(handout)| // vertices away (bending_neighbours, K = bending_stiffness()).
      // STUDENT(guided)| // TODO Q8 (bending springs): the same with bending_neighbours, two vertices
      // STUDENT(guided)| // away, s(ku+2, kv), s(ku, kv+2), s(ku-2, kv), s(ku, kv-2),
      // STUDENT(guided)| // K = bending_stiffness() and L0 = 2h.
      for (const auto [du, dv] : bending_neighbours) {
        if (!spring_intact(ku, kv, du, dv))
          continue;
        const std::size_t k2 = index(ku + du, kv + dv, N);
        const double L0 = glm::length(initial[k] - initial[k2]);
        f += spring_force(vertices[k], vertices[k2], bending_stiffness(), L0);
      }
      // END SOLUTION Q8

      // BEGIN SOLUTION Q13: wind
      // STUDENT(handout)| // TODO Q13 (wind): add the force of the wind on the vertex, the handout's
      // STUDENT(handout)| // F_w = K_w <n, u_w> n (section 5), K_w = parameters.wind_strength, u_w the
      // STUDENT(handout)| // unit direction of parameters.wind_direction, n = normals[k] the unit
      // STUDENT(handout)| // normal at the vertex (computed only when K_w != 0). Done when
      // STUDENT(handout)| // ./test.sh -L q13 passes and the cloth billows.
      // STUDENT(guided)| // TODO Q13 (wind): when K_w = parameters.wind_strength is not 0, add
      // STUDENT(guided)| // F_w = K_w <n, u_w> n, with n = normals[k] and u_w the unit wind direction,
      // STUDENT(guided)| // parameters.wind_direction / glm::length(parameters.wind_direction).
      const double K_w = parameters.wind_strength;  // N
      if (K_w != 0.0) {
        const glm::dvec3 u_w = parameters.wind_direction / glm::length(parameters.wind_direction);
        f += K_w * glm::dot(normals[k], u_w) * normals[k];
      }
      // END SOLUTION Q13

      forces[k] = f;
    }
  }
}

void apply_ground_contact(const cloth_parameters& parameters, particle_system& particles) {
  if (!parameters.ground_enabled)
    return;  // --ground-z none: no plane
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
    // STUDENT(handout)| // integration; z_g = parameters.ground_height, mu_g =
    // STUDENT(handout)| // parameters.ground_friction and the step dt = parameters.dynamics.time_step.
    // STUDENT(handout)| // Decide what becomes of the position and of each component of the
    // STUDENT(handout)| // velocity. For now the cloth falls through the floor. Done when
    // STUDENT(handout)| // ./test.sh -L q9 passes and the cloth lies on the checkerboard.
    // STUDENT(guided)| // TODO Q9 (ground): with z_g = parameters.ground_height, mu_g =
    // STUDENT(guided)| // parameters.ground_friction and dt = parameters.dynamics.time_step: if the
    // STUDENT(guided)| // vertex is below the plane (p.z < z_g), put it back on it (p.z = z_g), stop
    // STUDENT(guided)| // its fall (v.z = max(v.z, 0)) and damp its sliding by fluid friction:
    // STUDENT(guided)| // (v.x, v.y) *= (1 - mu_g dt). For now the cloth falls through the floor.
    const double z_g = parameters.ground_height;      // m
    const double mu_g = parameters.ground_friction;   // 1/s
    const double dt = parameters.dynamics.time_step;  // s
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
