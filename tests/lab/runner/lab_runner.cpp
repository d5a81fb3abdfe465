// The lab runner: the student's code (the physics core and the GPU cloth) in a process of its
// own, doing what the question tests ask, one request at a time (protocol.hpp), and answering
// what it computed. It decides nothing: the checks run in the question test programs, which
// start it (tests/lab/runner_client.cpp) and link none of the student's code.
//
// It is started with its requests and answers on fd 3; its standard output and error (the
// student's prints) are a pipe the checker reads apart. It ends when fd 3 closes.
#include <fcntl.h>
#if defined(__linux__)
#include <sys/prctl.h>
#endif
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/coupled_springs.hpp"
#include "core/particle_system.hpp"
#include "core/spring_mesh.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth.hpp"
#include "protocol.hpp"

namespace clothlab {
namespace {

namespace proto = lab_protocol;

constexpr std::size_t max_particles = 1 << 20;

// The objects the checker made, by the number it gave them.
struct objects {
  std::map<long long, std::unique_ptr<spring_mesh>> cloths;
  std::map<long long, std::unique_ptr<coupled_springs>> chains;
  std::map<long long, std::unique_ptr<gpu_cloth>> gpus;
  std::unique_ptr<gl_context> context;  // made at the first GPU request
};

template <class T>
T& find(std::map<long long, std::unique_ptr<T>>& table, long long id) {
  const auto it = table.find(id);
  if (it == table.end())
    throw std::invalid_argument("lab_runner: no object " + std::to_string(id));
  return *it->second;
}

// Sets the particles to the state the checker sent (same count).
void set_particles(particle_system& particles, const proto::particle_arrays& state) {
  if (state.is_fixed.size() != particles.size())
    throw std::invalid_argument("lab_runner: a state of " + std::to_string(state.is_fixed.size()) +
                                " particles for an object of " + std::to_string(particles.size()));
  particles.position = state.position;
  particles.velocity = state.velocity;
  particles.force = state.force;
  particles.is_fixed = state.is_fixed;
}

void put_particles(std::string& line, int grid_size, const particle_system& particles) {
  const std::size_t n = particles.size();
  if (particles.position.size() != 3 * n || particles.velocity.size() != 3 * n ||
      particles.force.size() != 3 * n)
    throw std::length_error(
        "the particle arrays position, velocity and force should hold 3n "
        "numbers each for n = " +
        std::to_string(n) + " particles");
  proto::put_particles(line, grid_size, particles.position, particles.velocity, particles.force,
                       particles.is_fixed);
}

// `<id> <parameters> <state>`: the cloth `id` with the checker's copy of its parameters and
// particles (what a test set by hand since the last request).
spring_mesh& synced_cloth(objects& o, proto::reader& in) {
  spring_mesh& cloth = find(o.cloths, in.integer(0, 1LL << 40));
  const auto p = in.parse_struct<cloth_parameters>();
  const proto::particle_arrays state = proto::read_particles(in, max_particles);
  if (!in.ok())
    throw std::invalid_argument("lab_runner: a malformed cloth request");
  cloth.parameters = p;
  set_particles(cloth.particles(), state);
  return cloth;
}

coupled_springs& synced_chain(objects& o, proto::reader& in) {
  coupled_springs& chain = find(o.chains, in.integer(0, 1LL << 40));
  const auto p = in.parse_struct<coupled_springs_parameters>();
  const proto::particle_arrays state = proto::read_particles(in, max_particles);
  if (!in.ok())
    throw std::invalid_argument("lab_runner: a malformed chain request");
  chain.parameters = p;
  set_particles(chain.particles(), state);
  return chain;
}

gl_context& context(objects& o) {
  if (!o.context) {
    std::string error;
    o.context = create_offscreen_context(16, 16, error);
    if (!o.context)
      throw std::runtime_error("no off-screen OpenGL context: " + error);
  }
  return *o.context;
}

// Does one request; returns the answer's results (after "ok").
std::string answer(objects& o, std::string_view request) {
  proto::reader in(request);
  const std::string_view operation = in.word();
  std::string out;
  if (operation == "cloth") {  // cloth <id> <parameters>: spring_mesh(p)
    const long long id = in.integer(0, 1LL << 40);
    const auto p = in.parse_struct<cloth_parameters>();
    if (!in.ok())
      throw std::invalid_argument("lab_runner: a malformed request");
    auto cloth = std::make_unique<spring_mesh>(p);
    put_particles(out, cloth->grid_size(), cloth->particles());
    o.cloths[id] = std::move(cloth);
  } else if (operation == "copy") {  // copy <new id> <id> <parameters> <state>
    const long long id = in.integer(0, 1LL << 40);
    auto copy = std::make_unique<spring_mesh>(synced_cloth(o, in));
    o.cloths[id] = std::move(copy);
  } else if (operation == "compute_force" || operation == "apply_force" ||
             operation == "apply_constraints" || operation == "step") {
    spring_mesh& cloth = synced_cloth(o, in);
    if (operation == "compute_force")
      cloth.compute_force();
    else if (operation == "apply_force")
      cloth.apply_force();
    else if (operation == "apply_constraints")
      cloth.apply_constraints();
    else
      cloth.step();
    put_particles(out, cloth.grid_size(), cloth.particles());
  } else if (operation == "springs") {  // springs <id>: each family's count, then a b L0 each
    const spring_mesh& cloth = find(o.cloths, in.integer(0, 1LL << 40));
    for (spring_family family : all_spring_families) {
      const auto list = cloth.springs(family);
      proto::put(out, static_cast<long long>(list.size()));
      for (const spring& s : list) {
        proto::put(out, static_cast<long long>(s.a));
        proto::put(out, static_cast<long long>(s.b));
        proto::put(out, s.rest_length);
      }
    }
  } else if (operation == "remove") {  // remove <id> <count> (<family> <a> <b>)...
    spring_mesh& cloth = find(o.cloths, in.integer(0, 1LL << 40));
    const long long count = in.integer(0, 1 << 24);
    std::vector<std::array<long long, 3>> torn(static_cast<std::size_t>(count));
    for (auto& t : torn)
      t = {in.integer(0, 2), in.integer(0, 1LL << 32), in.integer(0, 1LL << 32)};
    if (!in.ok())
      throw std::invalid_argument("lab_runner: a malformed request");
    const std::size_t removed = cloth.remove_springs([&](spring_family family, const spring& s) {
      for (const auto& t : torn)
        if (t[0] == static_cast<int>(family) && t[1] == s.a && t[2] == s.b)
          return true;
      return false;
    });
    proto::put(out, static_cast<long long>(removed));
  } else if (operation == "chain") {  // chain <id> <parameters>: coupled_springs(p)
    const long long id = in.integer(0, 1LL << 40);
    const auto p = in.parse_struct<coupled_springs_parameters>();
    if (!in.ok())
      throw std::invalid_argument("lab_runner: a malformed request");
    auto chain = std::make_unique<coupled_springs>(p);
    put_particles(out, 0, chain->particles());
    o.chains[id] = std::move(chain);
  } else if (operation == "chain_compute_force" || operation == "chain_step") {
    coupled_springs& chain = synced_chain(o, in);
    if (operation == "chain_compute_force")
      chain.compute_force();
    else
      chain.step();
    put_particles(out, 0, chain.particles());
  } else if (operation == "ground") {  // ground <z_g> <mu_g> <dt> <state>: apply_ground_contact
    const double height = in.number(), friction = in.number(), time_step = in.number();
    const proto::particle_arrays state = proto::read_particles(in, max_particles);
    if (!in.ok())
      throw std::invalid_argument("lab_runner: a malformed request");
    particle_system particles;
    particles.resize(state.is_fixed.size());
    set_particles(particles, state);
    cloth_parameters ground;  // the plane on, at z_g, with mu_g and dt
    ground.ground_enabled = true;
    ground.ground_height = height;
    ground.ground_friction = friction;
    ground.dynamics.time_step = time_step;
    apply_ground_contact(ground, particles);
    put_particles(out, 0, particles);
  } else if (operation == "gpu_load") {  // gpu_load <gpu id> <cloth id> <parameters> <state>
    const long long id = in.integer(0, 1LL << 40);
    context(o);
    spring_mesh& cloth = synced_cloth(o, in);
    auto& gpu = o.gpus[id];
    if (!gpu)
      gpu = std::make_unique<gpu_cloth>();
    std::string error;
    const bool loaded = gpu->load(cloth, error);
    proto::put(out, loaded ? 1LL : 0LL);
    proto::put_text(out, error);
  } else if (operation == "gpu_step") {  // gpu_step <gpu id> <parameters>
    gpu_cloth& gpu = find(o.gpus, in.integer(0, 1LL << 40));
    const auto p = in.parse_struct<cloth_parameters>();
    if (!in.ok())
      throw std::invalid_argument("lab_runner: a malformed request");
    gpu.step(p);
  } else if (operation == "gpu_read") {  // gpu_read <gpu id> <cloth id> <parameters> <state>
    const gpu_cloth& gpu = find(o.gpus, in.integer(0, 1LL << 40));
    spring_mesh& cloth = synced_cloth(o, in);
    gpu.read_state(cloth);
    put_particles(out, cloth.grid_size(), cloth.particles());
  } else {
    throw std::invalid_argument("lab_runner: unknown request '" + std::string(operation) + "'");
  }
  return out;
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0 && errno == EINTR)
      continue;
    if (written <= 0)
      return false;
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

}  // namespace
}  // namespace clothlab

int main() {
  using namespace clothlab;
  const int fd = lab_protocol::channel_fd;
  if (::fcntl(fd, F_GETFD) == -1) {
    std::fprintf(stderr,
                 "lab_runner: runs the student's code for the question tests (lab_q5_tests ...), "
                 "which start it with their requests on file descriptor %d\n",
                 fd);
    return 2;
  }
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);  // not handed to a program the student's code starts
#if defined(__linux__)
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // ends with the checker that started it
#endif
  std::signal(SIGPIPE, SIG_DFL);

  objects o;
  std::string buffer;
  char chunk[65536];
  for (;;) {
    const std::size_t end = buffer.find('\n');
    if (end == std::string::npos) {
      const ssize_t got = ::read(fd, chunk, sizeof chunk);
      if (got < 0 && errno == EINTR)
        continue;
      if (got <= 0)
        return 0;  // the checker is done
      buffer.append(chunk, static_cast<std::size_t>(got));
      continue;
    }
    const std::string request = buffer.substr(0, end);
    buffer.erase(0, end + 1);
    std::string reply;
    try {
      reply = "ok" + answer(o, request);
    } catch (const std::exception& e) {
      reply = "error";
      lab_protocol::put_text(reply, e.what());
    } catch (...) {
      reply = "error";
      lab_protocol::put_text(reply, "an exception that is not a std::exception");
    }
    std::fflush(stdout);  // the student's prints of this request come before its answer
    std::fflush(stderr);
    if (!write_all(fd, reply + "\n"))
      return 0;
  }
}
