#include "export.hpp"

#include <cerrno>
#include <memory>

namespace clothlab {

void write_csv_header(std::FILE* out) {
  std::fputs("step,t,particle,x,y,z,vx,vy,vz\n", out);
}

void write_csv_step(std::FILE* out, long step, double time, const particle_system& particles) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const double* p = &particles.position[3 * k];
    const double* v = &particles.velocity[3 * k];
    std::fprintf(out, "%ld,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, time, k, p[0],
                 p[1], p[2], v[0], v[1], v[2]);
  }
}

bool write_obj(const std::string& path, int n, const particle_system& particles,
               std::span<const double> normals) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file)
    return false;
  std::FILE* out = file.get();
  std::fprintf(out, "# clothlab cloth, %d x %d particles, vertex k = ku + N kv (1-based: k + 1)\n",
               n, n);
  const std::size_t count = particles.size();
  for (std::size_t k = 0; k < count; ++k) {
    const double* p = &particles.position[3 * k];
    std::fprintf(out, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
  }
  for (std::size_t k = 0; k < count; ++k) {
    const double* m = &normals[3 * k];
    std::fprintf(out, "vn %.17g %.17g %.17g\n", m[0], m[1], m[2]);
  }
  for (int kv = 0; kv < n; ++kv) {
    for (int ku = 0; ku < n; ++ku) {
      std::fprintf(out, "vt %.17g %.17g\n", double(ku) / (n - 1), double(kv) / (n - 1));
    }
  }
  // Two triangles per cell, counter-clockwise seen from +z on the flat cloth.
  for (int kv = 0; kv + 1 < n; ++kv) {
    for (int ku = 0; ku + 1 < n; ++ku) {
      const long a = long(ku) + long(n) * kv + 1;  // (ku, kv)
      const long b = a + 1;                        // (ku+1, kv)
      const long c = a + n + 1;                    // (ku+1, kv+1)
      const long d = a + n;                        // (ku, kv+1)
      std::fprintf(out, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c, c);
      std::fprintf(out, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, c, c, c, d, d, d);
    }
  }
  const bool ok = std::ferror(out) == 0;
  return std::fclose(file.release()) == 0 && ok;
}

}  // namespace clothlab
