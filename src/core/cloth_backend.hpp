// The cloth's simulation paths (questions 11 to 13), one name for the whole program: the command
// line's --backend, the window's switch, the headless runner and the cloth's paths all use it.
#pragma once

#include "core/i18n.hpp"  // N_: the window's names, translated where shown

namespace clothlab {

// The lab's readable CPU code (spring_mesh, double precision); the threaded and vectorised CPU
// path (cloth_parallel, double precision, teacher's copy); the handout's fragment-shader GPU path
// (gpu_cloth, single precision); the OpenGL 4.3 compute-shader GPU path (gpu_cloth_compute).
enum class cloth_backend { cpu, cpu_parallel, gpu, gpu_compute };

// As the window names it: "CPU", "CPU parallel", "GPU", "GPU compute".
constexpr const char* backend_name(cloth_backend backend) {
  switch (backend) {
    case cloth_backend::cpu_parallel:
      return N_("CPU parallel");
    case cloth_backend::gpu:
      return "GPU";
    case cloth_backend::gpu_compute:
      return N_("GPU compute");
    case cloth_backend::cpu:
      break;
  }
  return "CPU";
}

// As the command line names it (--backend): "cpu", "cpu-parallel", "gpu", "gpu-compute".
constexpr const char* backend_option(cloth_backend backend) {
  switch (backend) {
    case cloth_backend::cpu_parallel:
      return "cpu-parallel";
    case cloth_backend::gpu:
      return "gpu";
    case cloth_backend::gpu_compute:
      return "gpu-compute";
    case cloth_backend::cpu:
      break;
  }
  return "cpu";
}

// True for the paths that run on the GPU (they need an OpenGL context).
constexpr bool on_gpu(cloth_backend backend) {
  return backend == cloth_backend::gpu || backend == cloth_backend::gpu_compute;
}

}  // namespace clothlab
