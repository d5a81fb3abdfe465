// Question 12: how fast is one step of the cloth on each path: step/cpu/N (spring_mesh::step,
// the lab's readable code, double precision), step/cpu-parallel/N (cloth_parallel::step, the
// threaded, vectorised path, double precision, all cores) and step/gpu/N (gpu_cloth::step,
// fragment shaders, single precision) and step/gpu-compute/N (gpu_cloth_compute, compute
// shaders)? Each reports steps/s and the time per spring.
// The GPU step runs in an off-screen context chosen as clothlab chooses it (--gl auto|egl|osmesa,
// docs/cli.md): clothlab_bench holds an OSMesa context, clothlab_bench_egl (built beside it from
// this file) an EGL one, and the run is handed to the other one when the choice asks for it. On
// a machine without a GPU that is llvmpipe, Mesa's software rasteriser on the CPU, so it
// measures the shader path, not a GPU.
// Both run the default cloth (two pinned corners, ground) for N x N particles.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/cloth_parallel.hpp"
#include "core/spring_mesh.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"
#include "gl/gpu_cloth.hpp"
#include "gl/gpu_cloth_compute.hpp"
#include "gl/program_choice.hpp"
#include "gl/shader.hpp"

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
    state.SkipWithError(clothlab::cloth_parallel::unavailable_reason());
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
      std::fprintf(stderr, "clothlab_bench: OpenGL: %s, %s\n", made->description().c_str(),
                   made->origin().c_str());
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
    ->Arg(32)  // (scripts/benchmark-web: the browser's CPU path at N = 32 and 64)
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

// The paths a build may lack (OpenMP; the compute shader, which the student copy leaves out) are
// listed only where they exist: a run shows no row that could not run.
void register_optional_paths() {
  if (clothlab::cloth_parallel::available()) {
    benchmark::RegisterBenchmark("step/cpu-parallel", cpu_parallel_step)
        ->RangeMultiplier(2)
        ->Range(64, 1024)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  } else {
    std::fprintf(stderr, "clothlab_bench: no step/cpu-parallel: %s\n",
                 clothlab::cloth_parallel::unavailable_reason());
  }
  if (std::filesystem::exists(clothlab::shader_path("gpu_compute_step.comp"))) {
    benchmark::RegisterBenchmark("step/gpu-compute", gpu_compute_step)
        ->RangeMultiplier(2)
        ->Range(64, 2048)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  }
}

// --gl auto|egl|osmesa (default auto), taken off the arguments before Google Benchmark reads
// them; the run goes on here or in the program of the other context.
int main(int argc, char** argv) {
  std::string gl = "auto";
  std::vector<std::string> others;
  for (int i = 0; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument.rfind("--gl=", 0) == 0) {
      gl = argument.substr(5);
    } else if (argument == "--gl" && i + 1 < argc) {
      gl = argv[++i];
    } else {
      others.push_back(argument);
    }
  }
  if (gl != "auto" && gl != "egl" && gl != "osmesa") {
    std::fprintf(stderr, "clothlab_bench: --gl %s: must be auto, egl or osmesa\n", gl.c_str());
    return 2;
  }
#if defined(CLOTHLAB_EGL_PROGRAM)
  if (gl == "osmesa" || (gl == "auto" && !clothlab::egl_hardware_device_available()))
    return clothlab::hand_over_to("clothlab_bench", "clothlab_bench", others);
#elif defined(CLOTHLAB_EGL_BESIDE)
  if (gl == "egl" || (gl == "auto" && clothlab::gpu_device_node_present())) {
    others.push_back("--gl=egl");
    return clothlab::hand_over_to("clothlab_bench", "clothlab_bench_egl", others);
  }
#else
  // A build with one off-screen context (or a hidden window's): the run is here, whatever --gl.
#endif
  std::vector<char*> arguments;
  for (std::string& argument : others)
    arguments.push_back(argument.data());
  int count = static_cast<int>(arguments.size());
  register_optional_paths();
  benchmark::Initialize(&count, arguments.data());
  if (benchmark::ReportUnrecognizedArguments(count, arguments.data()))
    return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
