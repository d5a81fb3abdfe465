// Writing the state out: the CSV of cli.md and the cloth as a Wavefront OBJ.
#pragma once

#include <cstdio>
#include <span>
#include <string>

#include "particle_system.hpp"

namespace clothlab {

// "step,t,particle,x,y,z,vx,vy,vz" (cli.md).
void write_csv_header(std::FILE* out);
// One line per particle, in index order, numbers as %.17g so that they read back exactly.
void write_csv_step(std::FILE* out, long step, double time, const particle_system& particles);

// The N x N cloth: positions, normals, texture coordinates (u = ku/(N-1), v = kv/(N-1)) and two
// triangles per cell. Returns false (errno set) when the file cannot be written.
bool write_obj(const std::string& path, int n, const particle_system& particles,
               std::span<const double> normals);

}  // namespace clothlab
