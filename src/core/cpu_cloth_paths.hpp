// Questions 11 to 13: the cloth and the paths that can simulate it, in one object. This class
// holds the readable CPU cloth (spring_mesh, the lab's code, double precision), which the panel,
// the CSV and the OBJ read, and the parallel CPU path (cloth_parallel); gl/cloth_paths.hpp adds
// the two GPU paths. A run on the CPU paths alone (clothlab --headless --backend cpu or
// cpu-parallel) uses this class and so no OpenGL code.
// While a path other than the readable one runs the cloth, the state lives on that path and
// comes back into the CPU cloth only when read_state() is called:
//   - switching with the state carried across: read_state() from the path it is on, then load();
//   - stepping in batches with the divergence check done on the path itself (run), with the
//     parameters at this N (question 10) computed once per batch and handed to the path;
//   - reading back the whole state (read_state) or one particle (position).
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <string>

#include "core/cloth_backend.hpp"
#include "core/cloth_parallel.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

class cpu_cloth_paths {
 public:
  // The cloth of p, on the CPU path; threads: cpu-parallel's (0: all cores).
  explicit cpu_cloth_paths(const cloth_parameters& p, int threads = 0)
      : cloth(p), parallel_(threads) {}
  virtual ~cpu_cloth_paths() = default;
  cpu_cloth_paths(const cpu_cloth_paths&) = delete;
  cpu_cloth_paths& operator=(const cpu_cloth_paths&) = delete;

  // The readable cloth: its parameters are the ones every path runs with; its state is the
  // current one on the CPU path, and as of the last read_state() on the others.
  spring_mesh cloth;

  cloth_backend backend() const { return backend_; }
  // Uploads the cloth's current state (positions, velocities, pins, rest lengths, torn springs)
  // to `target`, which then holds it; the divergence check's speed bound is the cloth's
  // (divergence_speed_bound). The CPU target loads nothing. False with a full-sentence error
  // when the path cannot take it (here: a GPU path, or cpu-parallel where it is not built): the
  // cloth is then on the CPU path.
  virtual bool load(cloth_backend target, std::string& error);
  // The current path's state into the cloth (positions, velocities, the springs torn there);
  // nothing on the CPU path.
  virtual void read_state();
  // `count` steps on the current path (not the CPU: spring_mesh::step is the lesson's loop, run
  // by its callers), each checked there for divergence: returns the first step of the batch
  // (1..count) after which a particle was not finite or faster than speed_bound(), 0 if none.
  virtual int run(int count);
  double speed_bound() const { return speed_bound_; }  // m/s, set by load()
  // Particle k = ku + N kv's current position, m (on a GPU path one texel read back).
  virtual glm::dvec3 position(std::size_t k);

 protected:
  cloth_backend backend_ = cloth_backend::cpu;
  double speed_bound_ = 0.0;

 private:
  cloth_parallel parallel_;
};

}  // namespace clothlab
