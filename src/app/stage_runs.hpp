// The step loops of a headless run, for every path that needs no OpenGL context of its own: the
// three stages on the CPU (one spring_mesh::step, or single_spring's, coupled_springs', at a time)
// and the cloth's other paths in batches (cpu_cloth_paths, or cloth_paths for the GPU paths).
// After each step: the divergence check (exit 3), the outputs' rows (run_outputs), the progress
// line and the stop signals. Each returns the exit status: 0, 1 (a step threw: the line names
// the function), 3 or 128 + a stop signal.
#pragma once

#include "app/options.hpp"
#include "app/run_outputs.hpp"
#include "core/coupled_springs.hpp"
#include "core/cpu_cloth_paths.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {

// The CPU path, the same for the three stages: step 0 is the initial state, checked and written
// like every other, then o.steps steps.
int run_cpu(const options& o, single_spring& stage, run_outputs& out);
int run_cpu(const options& o, coupled_springs& stage, run_outputs& out);
int run_cpu(const options& o, spring_mesh& stage, run_outputs& out);

// The cloth on the path loaded in `paths` (cpu-parallel, gpu, gpu-compute), in batches.
int run_batched(const options& o, cpu_cloth_paths& paths, run_outputs& out);

}  // namespace clothlab
