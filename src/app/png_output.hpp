// --png: the final state drawn into the off-screen context with the stage's fixed camera, by the
// window's renderer, and written as a PNG (checked whole: run_outputs::check_png). Each returns
// the exit status (0, or 1 with the message reported). Needs the off-screen context current.
#pragma once

#include "app/options.hpp"
#include "app/run_outputs.hpp"
#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "gl/cloth_paths.hpp"

namespace clothlab {

int write_png(const options& o, run_outputs& out, const single_spring& stage);
int write_png(const options& o, run_outputs& out, const coupled_springs& stage);
int write_png(const options& o, run_outputs& out, const spring_mesh& cloth);
// The cloth on the fragment path, drawn from its own textures (no read-back).
int write_png(const options& o, run_outputs& out, cloth_paths& paths);

}  // namespace clothlab
