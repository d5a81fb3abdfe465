// Writing the state out: the CSV of cli.md and the cloth as a Wavefront OBJ, and the output
// file that every writer goes through so that a file is written whole or not at all.
#pragma once

#include <cstdio>
#include <functional>
#include <span>
#include <string>

#include "core/particle_system.hpp"

namespace clothlab {

// "step,t,particle,x,y,z,vx,vy,vz" (cli.md).
void write_csv_header(std::FILE* out);
// One line per particle, in index order, numbers as %.17g so that they read back exactly.
void write_csv_step(std::FILE* out, long step, double time, const particle_system& particles);
// The lines of particles first .. last - 1 only (a step written in parts).
void write_csv_rows(std::FILE* out, long step, double time, const particle_system& particles,
                    std::size_t first, std::size_t last);

// The N x N cloth: positions, normals, texture coordinates (u = ku/(N-1), v = kv/(N-1)) and two
// triangles per cell. A normal that is not a finite unit vector (a cell collapsed to a point)
// is written as (0, 0, 1). Returns false (errno set) when the file cannot be written.
// drawn(ku, kv, upper) says whether the lower triangle (ku, kv), (ku+1, kv), (ku+1, kv+1) or
// the upper one (ku, kv), (ku+1, kv+1), (ku, kv+1) of cell (ku, kv) is written (default: all;
// a torn cloth leaves out the triangles that lost a spring, spring_mesh::triangle_intact).
bool write_obj(const std::string& path, int n, const particle_system& particles,
               std::span<const double> normals,
               const std::function<bool(int ku, int kv, bool upper)>& drawn = {});

// True when the file is a PNG whose chunks run to an IEND chunk that ends the file: a PNG
// writer that does not report a failed write (stb's) leaves a file that fails this.
bool png_file_is_whole(const std::string& path);

// An output file written whole or not at all. The data go to a temporary file
// beside the target, ".NAME.XXXXXX" in the same folder, and commit() renames it over the
// target: a reader, or a second run writing the same file at the same time, sees the old file
// or a whole new one (the last rename wins), never a part; on failure the temporary file is
// removed and the target left as it was. A target that is not a regular file (/dev/stdout,
// /dev/full, a pipe) cannot be replaced: a stream writes to it directly, and a writer that
// needs a file name (the PNG) writes to a temporary file in the system's temporary folder that
// commit() copies into the target. Every write, flush and close is checked either way.
class output_file {
 public:
  enum class writer {
    stream,    // the caller opens write_path() itself and writes as it goes
    file_name  // the caller hands write_path() to a function that writes the whole file
  };

  output_file() = default;
  output_file(const output_file&) = delete;
  output_file& operator=(const output_file&) = delete;
  ~output_file();  // discard()

  // Prepares the target; false with `error` saying why (strerror) when it cannot be written.
  bool open(const std::string& target, writer kind, std::string& error);
  // Where to write: the temporary file, or the target itself when it is written directly.
  const std::string& write_path() const { return temporary_.empty() ? target_ : temporary_; }
  const std::string& target() const { return target_; }
  // Once the caller has closed write_path() without error: moves (or copies) the data into the
  // target. False with `error` saying what failed; the temporary file is removed either way.
  bool commit(std::string& error);
  // Removes the temporary file (the target is left as it was).
  void discard();
  // Removes the temporary file but keeps its name (safe while another thread reads
  // write_path()); discard() later does nothing more.
  void remove_temporary() const;

 private:
  std::string target_;
  std::string temporary_;  // empty: the target is written directly
  bool copy_into_target_ = false;
};

}  // namespace clothlab
