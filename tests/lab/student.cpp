#include "student.hpp"

#include <gtest/gtest.h>

#include "core/i18n.hpp"
#include "protocol.hpp"
#include "runner_client.hpp"

namespace clothlab::student {
namespace {

namespace proto = lab_protocol;

// The largest object a test makes is an 8 x 8 cloth; an answer is read up to this bound.
constexpr std::size_t max_particles = 1 << 16;

long long next_id() {
  static long long id = 0;
  return ++id;
}

std::optional<std::string> ask(const char* operation, const std::string& request) {
  return lab::runner::instance().ask(operation, request);
}

void put_state(std::string& line, int grid_size, const particle_system& p) {
  proto::put_particles(line, grid_size, p.position, p.velocity, p.force, p.is_fixed);
}

// A test fails, in the runner's words, when its answer is not what was asked for.
void wrong_answer(const char* operation, const std::string& what) {
  lab::runner::instance().reject(operation, what);
}

// The state of an answer, when it holds `count` particles (and, for a cloth, N = grid_size);
// nullopt (the test failed) otherwise.
std::optional<proto::particle_arrays> state_of(const std::string& answer, std::size_t count,
                                               int grid_size, const char* operation) {
  proto::reader in(answer);
  proto::particle_arrays state = proto::read_particles(in, max_particles);
  if (!in.ok() || !in.at_end()) {
    wrong_answer(operation, tr("answered a state that cannot be read"));
    return std::nullopt;
  }
  if (state.is_fixed.size() != count || state.grid_size != grid_size) {
    wrong_answer(
        operation,
        format(tr("left %zu particles (grid size %d) where there should be %zu"),
               state.is_fixed.size(), int(state.grid_size), std::size_t(count)) +
            (grid_size > 0 ? " (N x N, N = " + std::to_string(grid_size) + ")" : std::string()));
    return std::nullopt;
  }
  return state;
}

void take(particle_system& particles, proto::particle_arrays&& state) {
  particles.position = std::move(state.position);
  particles.velocity = std::move(state.velocity);
  particles.force = std::move(state.force);
  particles.is_fixed = std::move(state.is_fixed);
}

// How many particles an N x N cloth has (0 for a grid size no test uses).
std::size_t cloth_particles(int n) {
  return n > 0 && n <= 256 ? static_cast<std::size_t>(n) * static_cast<std::size_t>(n) : 0;
}

}  // namespace

spring_mesh::spring_mesh(const cloth_parameters& p) : parameters(p), id_(next_id()) {
  // Until the runner answers (or when it does not), the cloth a test expects: N x N particles.
  grid_size_ = p.grid_size;
  particles_.resize(cloth_particles(p.grid_size));
  std::string request = "cloth";
  proto::put(request, id_);
  proto::put_struct(request, parameters);
  const char* operation = tr("the spring_mesh constructor (load_model)");
  if (const auto answer = ask(operation, request))
    if (auto state = state_of(*answer, particles_.size(), grid_size_, operation))
      take(particles_, std::move(*state));
}

spring_mesh::spring_mesh(const spring_mesh& other)
    : parameters(other.parameters),
      id_(next_id()),
      grid_size_(other.grid_size_),
      particles_(other.particles_) {
  std::string request = "copy";
  proto::put(request, id_);
  request += ' ' + other.request_words();
  ask(tr("a copy of a spring_mesh"), request);
}

std::string spring_mesh::request_words() const {
  std::string words;
  proto::put(words, id_);
  proto::put_struct(words, parameters);
  put_state(words, grid_size_, particles_);
  return words.substr(1);
}

bool spring_mesh::take_state(const std::string& answer, const char* operation) {
  auto state = state_of(answer, particles_.size(), grid_size_, operation);
  if (!state)
    return false;
  take(particles_, std::move(*state));
  return true;
}

void spring_mesh::run(const char* request, const char* operation) {
  if (const auto answer = ask(operation, std::string(request) + ' ' + request_words()))
    take_state(*answer, operation);
}

void spring_mesh::compute_force() {
  run("compute_force", "spring_mesh::compute_force");
}
void spring_mesh::apply_force() {
  run("apply_force", "spring_mesh::apply_force");
}
void spring_mesh::apply_constraints() {
  run("apply_constraints", "spring_mesh::apply_constraints");
}
void spring_mesh::step() {
  run("step", "spring_mesh::step (compute_force, apply_force, apply_constraints)");
}

std::vector<std::vector<spring>> spring_mesh::springs() const {
  std::vector<std::vector<spring>> lists(3);
  std::string request = "springs";
  proto::put(request, id_);
  const char* operation = "spring_mesh::springs";
  const auto answer = ask(operation, request);
  if (!answer)
    return lists;
  proto::reader in(*answer);
  for (auto& list : lists) {
    const long long count = in.integer(0, 1 << 22);
    for (long long i = 0; i < count && in.ok(); ++i) {
      const auto a = static_cast<std::uint32_t>(in.integer(0, UINT32_MAX));
      const auto b = static_cast<std::uint32_t>(in.integer(0, UINT32_MAX));
      list.push_back({a, b, in.number()});
    }
  }
  if (!in.ok() || !in.at_end()) {
    wrong_answer(operation, tr("answered a list of springs that cannot be read"));
    return std::vector<std::vector<spring>>(3);
  }
  return lists;
}

std::size_t spring_mesh::remove(const std::vector<std::array<std::size_t, 3>>& chosen) {
  std::string request = "remove";
  proto::put(request, id_);
  proto::put(request, static_cast<long long>(chosen.size()));
  for (const auto& c : chosen)
    for (std::size_t x : c)
      proto::put(request, static_cast<long long>(x));
  const auto answer = ask("spring_mesh::remove_springs", request);
  if (!answer)
    return 0;
  proto::reader in(*answer);
  return static_cast<std::size_t>(in.integer(0, 1 << 30));
}

coupled_springs::coupled_springs(const coupled_springs_parameters& p)
    : parameters(p), id_(next_id()) {
  const std::size_t count = p.mass_count >= 0 && p.mass_count < 1000
                                ? static_cast<std::size_t>(p.mass_count) + 1
                                : 0;  // p0 and the n masses
  particles_.resize(count);
  std::string request = "chain";
  proto::put(request, id_);
  proto::put_struct(request, parameters);
  const char* operation = tr("the coupled_springs constructor (load_model)");
  if (const auto answer = ask(operation, request))
    if (auto state = state_of(*answer, count, 0, operation))
      take(particles_, std::move(*state));
}

void coupled_springs::run(const char* request, const char* operation) {
  std::string line = request;
  proto::put(line, id_);
  proto::put_struct(line, parameters);
  put_state(line, 0, particles_);
  if (const auto answer = ask(operation, line))
    if (auto state = state_of(*answer, particles_.size(), 0, operation))
      take(particles_, std::move(*state));
}

void coupled_springs::compute_force() {
  run("chain_compute_force", "coupled_springs::compute_force");
}
void coupled_springs::step() {
  run("chain_step", "coupled_springs::step (compute_force, apply_force)");
}

gpu_cloth::gpu_cloth() : id_(next_id()) {}

bool gpu_cloth::load(const spring_mesh& cloth, std::string& error) {
  std::string request = "gpu_load";
  proto::put(request, id_);
  request += ' ' + cloth.request_words();
  const char* operation = tr("gpu_cloth::load (the GPU programs, shaders/)");
  const auto answer = ask(operation, request);
  if (!answer) {
    error = tr("(the runner did not answer)");
    return false;
  }
  proto::reader in(*answer);
  const long long loaded = in.integer(0, 1);
  error = in.text(64 * 1024);
  if (!in.ok() || !in.at_end()) {
    wrong_answer(operation, tr("answered something that cannot be read"));
    return false;
  }
  return loaded == 1;
}

void gpu_cloth::step(const cloth_parameters& p) {
  std::string request = "gpu_step";
  proto::put(request, id_);
  proto::put_struct(request, p);
  ask("gpu_cloth::step (shaders/gpu_step.frag)", request);
}

void gpu_cloth::read_state(spring_mesh& cloth) const {
  std::string request = "gpu_read";
  proto::put(request, id_);
  request += ' ' + cloth.request_words();
  const char* operation = "gpu_cloth::read_state";
  if (const auto answer = ask(operation, request))
    cloth.take_state(*answer, operation);
}

void apply_ground_contact(double ground_height, double ground_friction, double time_step,
                          particle_system& particles) {
  std::string request = "ground";
  proto::put(request, ground_height);
  proto::put(request, ground_friction);
  proto::put(request, time_step);
  put_state(request, 0, particles);
  const char* operation = "apply_ground_contact";
  if (const auto answer = ask(operation, request))
    if (auto state = state_of(*answer, particles.size(), 0, operation))
      take(particles, std::move(*state));
}

}  // namespace clothlab::student
