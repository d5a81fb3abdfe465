#include "core/cpu_cloth_paths.hpp"

#include <stdexcept>

#include "core/i18n.hpp"
#include "core/stability.hpp"

namespace clothlab {

bool cpu_cloth_paths::load(cloth_backend target, std::string& error) {
  // Question 4's bound, from the cloth as loaded: a particle faster than it has diverged.
  speed_bound_ = divergence_speed_bound(cloth);
  bool loaded = true;
  switch (target) {
    case cloth_backend::cpu:
      break;
    case cloth_backend::cpu_parallel:
      try {
        parallel_.load(cloth);
      } catch (const std::invalid_argument& e) {  // not built: cloth_parallel_absent.cpp
        error = e.what();
        loaded = false;
      }
      break;
    case cloth_backend::gpu:
    case cloth_backend::gpu_compute:
      error = format(tr("the %s path needs OpenGL, which this program does not use"),
                     tr(backend_name(target)));
      loaded = false;
      break;
  }
  backend_ = loaded ? target : cloth_backend::cpu;
  return loaded;
}

void cpu_cloth_paths::read_state() {
  if (backend_ == cloth_backend::cpu_parallel)
    parallel_.read_state(cloth);
}

int cpu_cloth_paths::run(int count) {
  if (backend_ == cloth_backend::cpu_parallel)
    return parallel_.run(cloth.effective_parameters(), count, speed_bound_);
  throw std::logic_error("cloth_paths::run: the CPU path is stepped by spring_mesh::step");
}

glm::dvec3 cpu_cloth_paths::position(std::size_t k) {
  read_state();
  return cloth.particles().get_position(k);
}

}  // namespace clothlab
