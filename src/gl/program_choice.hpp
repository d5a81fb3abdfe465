// Which program runs a headless OpenGL job: clothlab and clothlab_bench hold an OSMesa context
// (software), clothlab-egl and clothlab_bench_egl an EGL one (a GPU where there is one), built
// from the same sources; --gl auto|egl|osmesa chooses (docs/cli.md). One process cannot link
// both libraries, so the choice hands the run over to the program beside it.
#pragma once

#include <string>
#include <vector>

namespace clothlab {

// A GPU's device node: Linux's DRM render nodes, or NVIDIA's. Without one, EGL has only Mesa's
// software renderer to offer, which OSMesa is too.
bool gpu_device_node_present();

// Replaces this process by the program `name` in this executable's folder, with `arguments`
// (argv[0] first). Returns only on failure, after printing why (prefixed by `who`): 1.
int hand_over_to(const char* who, const char* name, const std::vector<std::string>& arguments);

}  // namespace clothlab
