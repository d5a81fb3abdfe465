// Question 12: how fast is one step of the cloth on each path: step/cpu/N (spring_mesh::step,
// the lab's readable code, double precision), step/cpu-parallel/N (cloth_parallel::step, the
// threaded, vectorised path, double precision, all cores) and step/gpu/N (gpu_cloth::step,
// fragment shaders, single precision) and step/gpu-compute/N (gpu_cloth_compute, compute
// shaders)? Each reports steps/s and the time per spring.
// The GPU step runs in an off-screen OSMesa context: on a machine without a GPU that is
// llvmpipe, Mesa's software rasteriser on the CPU, so it measures the shader path, not a GPU.
// Both run the default cloth (two pinned corners, ground) for N x N particles.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <string>

#include "cloth_parallel.hpp"
#include "gl.hpp"
#include "gl_context.hpp"
#include "gpu_cloth.hpp"
#include "gpu_cloth_compute.hpp"
#include "spring_mesh.hpp"

namespace {

clothlab::cloth_parameters cloth_of_size(int n) {
  clothlab::cloth_parameters p;
  p.grid_size = n;
  return p;
}

// steps/s, and the time per spring (each spring of the three families counted once).
void count_steps(benchmark::State& state, int n) {
  const double springs = 2.0 * n * (n - 1) + 2.0 * (n - 1) * (n - 1) + 2.0 * n * (n - 2);
  const auto steps = static_cast<double>(state.iterations());
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["s/spring"] = benchmark::Counter(
      steps * springs, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void cpu_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  clothlab::spring_mesh cloth(cloth_of_size(n));
  for (auto _ : state) {
    cloth.step();
    benchmark::DoNotOptimize(cloth.particles().position.data());
  }
  count_steps(state, n);
}

void cpu_parallel_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const clothlab::cloth_parameters p = cloth_of_size(n);
  if (!clothlab::cloth_parallel::available()) {
    state.SkipWithError(clothlab::cloth_parallel::unavailable);
    return;
  }
  clothlab::spring_mesh cloth(p);
  clothlab::cloth_parallel fast;  // all cores
  fast.load(cloth);
  for (auto _ : state)
    fast.step(p);
  count_steps(state, n);
  state.counters["threads"] = fast.threads();
}

// One context for every GPU benchmark, made on first use.
clothlab::gl_context* offscreen_context() {
  static std::unique_ptr<clothlab::gl_context> context = [] {
    std::string error;
    auto made = clothlab::create_offscreen_context(16, 16, error);
    if (!made)
      std::fprintf(stderr, "clothlab_bench: %s\n", error.c_str());
    else
      std::fprintf(stderr, "clothlab_bench: OpenGL: %s\n", made->description().c_str());
    return made;
  }();
  return context.get();
}

void gpu_step(benchmark::State& state) {
  if (offscreen_context() == nullptr) {
    state.SkipWithError("no off-screen OpenGL context");
    return;
  }
  const clothlab::cloth_parameters p = cloth_of_size(static_cast<int>(state.range(0)));
  clothlab::spring_mesh cloth(p);
  clothlab::gpu_cloth gpu;
  std::string error;
  if (!gpu.load(cloth, error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (auto _ : state) {
    gpu.step(p);
    glFinish();  // count the rendering, not only its submission
  }
  count_steps(state, static_cast<int>(state.range(0)));
}

void gpu_compute_step(benchmark::State& state) {
  if (offscreen_context() == nullptr) {
    state.SkipWithError("no off-screen OpenGL context");
    return;
  }
  const int n = static_cast<int>(state.range(0));
  const clothlab::cloth_parameters p = cloth_of_size(n);
  clothlab::spring_mesh cloth(p);
  clothlab::gpu_cloth_compute gpu;
  std::string error;
  if (!gpu.load(cloth, error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (auto _ : state) {
    gpu.run(p);
    glFinish();
  }
  count_steps(state, n);
}

}  // namespace

// Wall-clock time: the threads of cpu-parallel and of llvmpipe are missed by the process's
// CPU time of the main thread.
BENCHMARK(cpu_step)
    ->Name("step/cpu")
    ->RangeMultiplier(2)
    ->Range(64, 1024)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(cpu_parallel_step)
    ->Name("step/cpu-parallel")
    ->RangeMultiplier(2)
    ->Range(64, 1024)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(gpu_step)
    ->Name("step/gpu")
    ->RangeMultiplier(2)
    ->Range(64, 2048)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(gpu_compute_step)
    ->Name("step/gpu-compute")
    ->RangeMultiplier(2)
    ->Range(64, 2048)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
