// The student's code as the question tests see it: stand-ins with the names and calls of
// clothlab's own classes (spring_mesh, coupled_springs, particle_system, gpu_cloth,
// apply_ground_contact), whose work is done by the lab runner, the student's code in a process
// of its own (runner_client.hpp). The tests read like calls of the student's functions; no
// student code is linked into a test program.
//
// Each stand-in keeps the state the test sees (particles(), parameters) here: a test sets it by
// hand as on the real class; each call of the student's code sends that state to the runner,
// runs the student's function there and takes back the state it left. When the runner fails
// (the test then fails, saying why), the state stays as it was.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "core/spring.hpp"

namespace clothlab::student {

// The particle arrays, laid out as in clothlab::particle_system (coordinate c of particle k at
// 3k + c), held by the test.
struct particle_system {
  std::vector<double> position;        // p, m
  std::vector<double> velocity;        // v, m/s
  std::vector<double> force;           // F, N
  std::vector<std::uint8_t> is_fixed;  // 1: never moves

  std::size_t size() const { return is_fixed.size(); }
  void resize(std::size_t n) {
    position.assign(3 * n, 0.0);
    velocity.assign(3 * n, 0.0);
    force.assign(3 * n, 0.0);
    is_fixed.assign(n, 0);
  }
  glm::dvec3 get_position(std::size_t k) const { return at(position, k); }
  glm::dvec3 get_velocity(std::size_t k) const { return at(velocity, k); }
  glm::dvec3 get_force(std::size_t k) const { return at(force, k); }
  void set_position(std::size_t k, const glm::dvec3& p) { put(position, k, p); }
  void set_velocity(std::size_t k, const glm::dvec3& v) { put(velocity, k, v); }

 private:
  static glm::dvec3 at(const std::vector<double>& a, std::size_t k) {
    return {a[3 * k], a[3 * k + 1], a[3 * k + 2]};
  }
  static void put(std::vector<double>& a, std::size_t k, const glm::dvec3& v) {
    for (int c = 0; c < 3; ++c)
      a[3 * k + c] = v[c];
  }
};

// The families of clothlab::spring_family (spring_mesh.hpp), in its order.
enum class spring_family { structural, shear, bending };

// The student's spring_mesh (questions 6 to 9 and 13).
class spring_mesh {
 public:
  cloth_parameters parameters;

  // The constructor (load_model: the grid, its springs, its pins, question 7).
  explicit spring_mesh(const cloth_parameters& p = {});
  spring_mesh(const spring_mesh& other);  // a copy of the student's cloth, state and springs
  spring_mesh(spring_mesh&& other) noexcept = default;
  spring_mesh& operator=(const spring_mesh&) = delete;

  void compute_force();      // question 8 (and 13)
  void apply_force();        // question 6
  void apply_constraints();  // question 9's ground, among others
  void step();               // compute_force, apply_force, apply_constraints

  int grid_size() const { return grid_size_; }
  static std::size_t index(int ku, int kv, int n) {
    return static_cast<std::size_t>(ku) + static_cast<std::size_t>(n) * kv;
  }
  particle_system& particles() { return particles_; }
  const particle_system& particles() const { return particles_; }

  // Removes every spring s of every family for which torn(family, s) is true (tearing).
  template <class Predicate>
  std::size_t remove_springs(Predicate torn) {
    std::vector<std::array<std::size_t, 3>> chosen;
    const std::vector<std::vector<spring>> lists = springs();
    for (int f = 0; f < 3; ++f)
      for (const spring& s : lists[std::size_t(f)])
        if (torn(static_cast<spring_family>(f), s))
          chosen.push_back({std::size_t(f), s.a, s.b});
    return remove(chosen);
  }

  long long id() const { return id_; }
  // `<id> <parameters> <state>`, the request's words that carry this cloth (protocol.hpp).
  std::string request_words() const;
  // Takes the state of an answer; false (and the test fails) when it is not this cloth's.
  bool take_state(const std::string& answer, const char* operation);

 private:
  long long id_ = -1;
  int grid_size_ = 0;
  particle_system particles_;

  void run(const char* request, const char* operation);
  std::vector<std::vector<spring>> springs() const;
  std::size_t remove(const std::vector<std::array<std::size_t, 3>>& chosen);
};

// The student's coupled_springs (question 5).
class coupled_springs {
 public:
  coupled_springs_parameters parameters;

  explicit coupled_springs(const coupled_springs_parameters& p = {});
  coupled_springs(coupled_springs&& other) noexcept = default;

  void compute_force();
  void step();

  particle_system& particles() { return particles_; }
  const particle_system& particles() const { return particles_; }

 private:
  long long id_ = -1;
  particle_system particles_;

  void run(const char* request, const char* operation);
};

// The student's GPU cloth (questions 9, 12 and 13 on the GPU), in the runner's off-screen
// OpenGL context.
class gpu_cloth {
 public:
  gpu_cloth();
  gpu_cloth(const gpu_cloth&) = delete;
  gpu_cloth& operator=(const gpu_cloth&) = delete;

  // Uploads the cloth's current state; false with the error (a shader that does not compile).
  bool load(const spring_mesh& cloth, std::string& error);
  void step(const cloth_parameters& p);
  // Copies the GPU's positions and velocities into cloth.particles().
  void read_state(spring_mesh& cloth) const;

 private:
  long long id_;
};

// The student's ground contact on the CPU (question 9).
void apply_ground_contact(double ground_height, double ground_friction, double time_step,
                          particle_system& particles);

}  // namespace clothlab::student
