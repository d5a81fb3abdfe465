// Question 12: how fast is one step of the cloth on each path: step/cpu/N (spring_mesh::step,
// the lab's readable code, double precision), step/cpu-parallel/N (cloth_parallel::step, the
// threaded, vectorised path, double precision, all cores) and step/gpu/N (gpu_cloth::step,
// fragment shaders, single precision) and step/gpu-compute/N (gpu_cloth_compute, compute
// shaders)? Each reports steps/s and the time per spring. step/gpu* waits for the GPU after
// every step (glFinish): the latency of one step. batch/gpu*/N runs 100 steps per batch and
// waits once, as a headless run does: the GPU's throughput, its steps pipelined.
// Every benchmark warms up before it is timed (the library's warm-up, 0.2 s unless
// --benchmark_min_warmup_time says otherwise); the GPU paths, whose clock rises under load (on an
// H200 the first run at 2048^2 read 22 ms per step, the next 5 ms), also until two timings agree
// (warm_up_until_steady).
// The GPU step runs in an off-screen context chosen as clothlab chooses it (--gl auto|egl|osmesa,
// docs/cli.md): clothlab_bench holds an OSMesa context, clothlab_bench_egl (built beside it from
// this file) an EGL one, and the run is handed to the other one when the choice asks for it. On
// a machine without a GPU that is llvmpipe, Mesa's software rasteriser on the CPU, so it
// measures the shader path, not a GPU.
// Both run the default cloth (two pinned corners, ground) for N x N particles.
// xpbd/<backend>/N: the same cloth stepped by XPBD (--integrator xpbd, its default 10 substeps of
// one sweep) on the paths that have it (cpu, cpu-parallel, gpu-compute), at the same dt: a step
// of XPBD against a step of the mass-spring paths. scripts/benchmark puts them side by side with
// the largest dt each integrator stays stable at (a clothlab --sweep), which is what a step buys.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/cloth_parallel.hpp"
#include "core/spring_mesh.hpp"
#include "core/xpbd.hpp"
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

clothlab::cloth_parameters xpbd_cloth_of_size(int n) {
  clothlab::cloth_parameters p = cloth_of_size(n);
  p.dynamics.integrator = clothlab::integrator_kind::xpbd;
  return p;
}

// steps/s, and the time per spring (each spring of the three families counted once), for
// steps_per_iteration steps per iteration of the benchmark's loop.
void count_steps(benchmark::State& state, int n, int steps_per_iteration = 1) {
  const double springs = 2.0 * n * (n - 1) + 2.0 * (n - 1) * (n - 1) + 2.0 * n * (n - 2);
  const auto steps = static_cast<double>(state.iterations()) * steps_per_iteration;
  state.counters["steps/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["s/spring"] = benchmark::Counter(
      steps * springs, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

template <clothlab::cloth_parameters (*Cloth)(int) = cloth_of_size>
void cpu_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  clothlab::spring_mesh cloth(Cloth(n));
  for (auto _ : state) {
    cloth.step();
    benchmark::DoNotOptimize(cloth.particles().position.data());
  }
  count_steps(state, n);
}

template <clothlab::cloth_parameters (*Cloth)(int) = cloth_of_size>
void cpu_parallel_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const clothlab::cloth_parameters p = Cloth(n);
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

// Runs `run_and_wait(count)` (count steps, then waiting for the GPU) in blocks of at least 20 ms
// until two blocks in a row agree within 5 % on the time per step, or for 3 s at most: the GPU's
// clock has then risen to what the benchmark will measure.
template <typename RunAndWait>
void warm_up_until_steady(RunAndWait run_and_wait) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  double previous = 0.0;  // s per step of the last block
  while (std::chrono::duration<double>(clock::now() - start).count() < 3.0) {
    const auto block_start = clock::now();
    int steps = 0;
    double seconds = 0.0;
    while (seconds < 0.02) {
      run_and_wait(1);
      ++steps;
      seconds = std::chrono::duration<double>(clock::now() - block_start).count();
    }
    const double per_step = seconds / steps;
    if (previous > 0.0 && std::abs(per_step - previous) <= 0.05 * previous)
      return;
    previous = per_step;
  }
}

// One benchmark's GPU path, loaded with the default cloth of size n: its run(p, count), then
// glFinish. Path: gpu_cloth or gpu_cloth_compute.
template <typename Path, clothlab::cloth_parameters (*Cloth)(int) = cloth_of_size>
struct loaded_gpu_path {
  clothlab::cloth_parameters parameters;
  Path path;
  bool loaded = false;

  loaded_gpu_path(benchmark::State& state, int n) : parameters(Cloth(n)) {
    if (offscreen_context() == nullptr) {
      state.SkipWithError("no off-screen OpenGL context");
      return;
    }
    const clothlab::spring_mesh cloth(parameters);
    std::string error;
    if (!path.load(cloth, error)) {
      state.SkipWithError(error.c_str());
      return;
    }
    loaded = true;
    // Once per path, cloth and size: the library calls a benchmark again for each count of
    // iterations it tries, and the GPU is warm by then.
    static std::set<int> warmed_up;
    if (warmed_up.insert(n).second)
      warm_up_until_steady([this](int count) { run_and_wait(count); });
  }
  void run_and_wait(int count) {
    path.run(parameters, count);
    glFinish();  // count the GPU's work, not only its submission
  }
};

// One step, then waiting for it: step/gpu/N and step/gpu-compute/N.
template <typename Path, clothlab::cloth_parameters (*Cloth)(int) = cloth_of_size>
void gpu_step(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  loaded_gpu_path<Path, Cloth> gpu(state, n);
  if (!gpu.loaded)
    return;
  for (auto _ : state)
    gpu.run_and_wait(1);
  count_steps(state, n);
}

// Steps in batches, waiting once per batch: batch/gpu/N and batch/gpu-compute/N.
constexpr int steps_per_batch = 100;

template <typename Path>
void gpu_batch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  loaded_gpu_path<Path> gpu(state, n);
  if (!gpu.loaded)
    return;
  for (auto _ : state)
    gpu.run_and_wait(steps_per_batch);
  count_steps(state, n, steps_per_batch);
}

}  // namespace

// Wall-clock time: the threads of cpu-parallel and of llvmpipe are missed by the process's
// CPU time of the main thread.
BENCHMARK(cpu_step<>)
    ->Name("step/cpu")
    ->Arg(32)  // (scripts/benchmark-web: the browser's CPU path at N = 32 and 64)
    ->RangeMultiplier(2)
    ->Range(64, 1024)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(gpu_step<clothlab::gpu_cloth>)
    ->Name("step/gpu")
    ->RangeMultiplier(2)
    ->Range(64, 2048)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(gpu_batch<clothlab::gpu_cloth>)
    ->Name("batch/gpu")
    ->RangeMultiplier(2)
    ->Range(64, 2048)
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

// The paths a build may lack (OpenMP; the compute shader, which the student copy leaves out) are
// listed only where they exist: a run shows no row that could not run.
void register_optional_paths() {
  if (clothlab::cloth_parallel::available()) {
    benchmark::RegisterBenchmark("step/cpu-parallel", cpu_parallel_step<>)
        ->RangeMultiplier(2)
        ->Range(64, 1024)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
  } else {
    std::fprintf(stderr, "clothlab_bench: no step/cpu-parallel: %s\n",
                 clothlab::cloth_parallel::unavailable_reason());
  }
  // XPBD, where this copy has it (not the student's).
  if (clothlab::xpbd_available()) {
    benchmark::RegisterBenchmark("xpbd/cpu", cpu_step<xpbd_cloth_of_size>)
        ->RangeMultiplier(2)
        ->Range(64, 256)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
    if (clothlab::cloth_parallel::available()) {
      benchmark::RegisterBenchmark("xpbd/cpu-parallel", cpu_parallel_step<xpbd_cloth_of_size>)
          ->RangeMultiplier(2)
          ->Range(64, 256)
          ->UseRealTime()
          ->Unit(benchmark::kMicrosecond);
    }
    if (std::filesystem::exists(clothlab::shader_path("gpu_xpbd_solve.comp"))) {
      benchmark::RegisterBenchmark("xpbd/gpu-compute",
                                   gpu_step<clothlab::gpu_cloth_compute, xpbd_cloth_of_size>)
          ->RangeMultiplier(2)
          ->Range(64, 256)
          ->UseRealTime()
          ->Unit(benchmark::kMicrosecond);
    }
  }
  if (std::filesystem::exists(clothlab::shader_path("gpu_compute_step.comp"))) {
    benchmark::RegisterBenchmark("step/gpu-compute", gpu_step<clothlab::gpu_cloth_compute>)
        ->RangeMultiplier(2)
        ->Range(64, 2048)
        ->UseRealTime()
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("batch/gpu-compute", gpu_batch<clothlab::gpu_cloth_compute>)
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
  // The library's warm-up before every benchmark, unless the command line sets its own.
  bool warm_up_given = false;
  for (const std::string& argument : others)
    warm_up_given = warm_up_given || argument.rfind("--benchmark_min_warmup_time", 0) == 0;
  if (!warm_up_given)
    others.push_back("--benchmark_min_warmup_time=0.2");
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
