// Question 12: how fast is one step of the cloth on the CPU (spring_mesh::step, double
// precision) and on the GPU (gpu_cloth::step, fragment shaders, single precision)?
// The GPU step runs in an off-screen OSMesa context: on a machine without a GPU that is
// llvmpipe, Mesa's software rasteriser on the CPU, so it measures the shader path, not a GPU.
// Both run the default cloth (two pinned corners, ground) for N x N particles.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <string>

#include "gl.hpp"
#include "gl_context.hpp"
#include "gpu_cloth.hpp"
#include "spring_mesh.hpp"

namespace {

clothlab::cloth_parameters cloth_of_size(int n) {
  clothlab::cloth_parameters p;
  p.grid_size = n;
  return p;
}

void cpu_step(benchmark::State& state) {
  clothlab::spring_mesh cloth(cloth_of_size(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    cloth.step();
    benchmark::DoNotOptimize(cloth.particles().position.data());
  }
  state.counters["particles"] = static_cast<double>(cloth.particles().size());
}

// One context for every GPU benchmark, made on first use.
clothlab::gl_context* offscreen_context() {
  static std::unique_ptr<clothlab::gl_context> context = [] {
    std::string error;
    auto made = clothlab::create_offscreen_context(16, 16, error);
    if (!made)
      std::fprintf(stderr, "clothlab_bench: %s\n", error.c_str());
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
  state.counters["particles"] = static_cast<double>(cloth.particles().size());
}

}  // namespace

BENCHMARK(cpu_step)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);
// Wall-clock time: llvmpipe renders on its own threads, which the process CPU time misses.
BENCHMARK(gpu_step)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

BENCHMARK_MAIN();
