#include "core/export.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

using file_handle = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// The permissions a newly created file gets: 0666 less the process's umask.
mode_t new_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

// Creates an empty file named after `pattern` (ending in XXXXXX) with the ordinary permissions;
// false with errno set.
bool create_temporary(std::string& pattern) {
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0)
    return false;
  const bool ok = ::fchmod(fd, new_file_mode()) == 0;
  const int saved = errno;
  ::close(fd);
  if (!ok) {
    ::unlink(pattern.c_str());
    errno = saved;
  }
  return ok;
}

std::uint32_t big_endian_32(const unsigned char* b) {
  return (std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) |
         std::uint32_t(b[3]);
}

}  // namespace

void write_csv_header(std::FILE* out) {
  std::fputs("step,t,particle,x,y,z,vx,vy,vz\n", out);
}

void write_csv_step(std::FILE* out, long step, double time, const particle_system& particles) {
  write_csv_rows(out, step, time, particles, 0, particles.size());
}

void write_csv_rows(std::FILE* out, long step, double time, const particle_system& particles,
                    std::size_t first, std::size_t last) {
  for (std::size_t k = first; k < last; ++k) {
    const double* p = &particles.position[3 * k];
    const double* v = &particles.velocity[3 * k];
    std::fprintf(out, "%ld,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, time, k, p[0],
                 p[1], p[2], v[0], v[1], v[2]);
  }
}

bool write_obj(const std::string& path, int n, const particle_system& particles,
               std::span<const double> normals,
               const std::function<bool(int ku, int kv, bool upper)>& drawn) {
  file_handle file(std::fopen(path.c_str(), "w"), &std::fclose);
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
    // A vertex whose triangles have no area (the cloth folded onto a point, or a side so small
    // that the cross products underflow) has no normal: any unit vector will do, +z.
    const double length = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (std::isfinite(length) && std::abs(length - 1.0) < 1e-3) {
      std::fprintf(out, "vn %.17g %.17g %.17g\n", m[0], m[1], m[2]);
    } else {
      std::fputs("vn 0 0 1\n", out);
    }
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
      if (!drawn || drawn(ku, kv, false))
        std::fprintf(out, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, b, b, b, c, c, c);
      if (!drawn || drawn(ku, kv, true))
        std::fprintf(out, "f %ld/%ld/%ld %ld/%ld/%ld %ld/%ld/%ld\n", a, a, a, c, c, c, d, d, d);
    }
  }
  const bool ok = std::ferror(out) == 0;
  return std::fclose(file.release()) == 0 && ok;
}

// PNG: an 8-byte signature, then chunks of (length, type, data, CRC), the last one IEND.
bool png_file_is_whole(const std::string& path) {
  file_handle file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file)
    return false;
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char header[8];
  if (std::fread(header, 1, 8, file.get()) != 8 || std::memcmp(header, signature, 8) != 0)
    return false;
  for (;;) {
    unsigned char chunk[8];  // length, type
    if (std::fread(chunk, 1, 8, file.get()) != 8)
      return false;
    const long length = static_cast<long>(big_endian_32(chunk));
    if (length < 0 || std::fseek(file.get(), length + 4, SEEK_CUR) != 0)  // data and CRC
      return false;
    if (std::memcmp(chunk + 4, "IEND", 4) == 0) {
      const long end = std::ftell(file.get());
      return std::fseek(file.get(), 0, SEEK_END) == 0 && std::ftell(file.get()) == end;
    }
  }
}

output_file::~output_file() {
  discard();
}

namespace {

// A temporary file's name pattern in the system's temporary folder (TMPDIR, else /tmp); empty,
// with the error set, when that folder cannot be used.
std::string temporary_pattern(std::string& error) {
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::temp_directory_path(ec);
  if (ec) {
    error = tr("the temporary folder (TMPDIR)") + std::string(colon()) + ec.message();
    return {};
  }
  return (folder / "clothlab-XXXXXX").string();
}

}  // namespace

bool output_file::open(const std::string& target, writer kind, std::string& error) {
  discard();
  target_ = target;
  copy_into_target_ = false;
  struct stat info {};
  const bool exists = ::stat(target.c_str(), &info) == 0;
  if (exists && !S_ISREG(info.st_mode)) {
    // A device or a pipe: it cannot be replaced by a rename.
    if (kind == writer::stream) {
      return true;  // written directly
    }
    temporary_ = temporary_pattern(error);
    if (temporary_.empty())
      return false;
    copy_into_target_ = true;
  } else {
    const std::filesystem::path path(target);
    const std::string name = path.filename().string();
    temporary_ = (path.parent_path() / ("." + name + ".XXXXXX")).string();
  }
  if (create_temporary(temporary_))
    return true;
  const int saved = errno;
  temporary_.clear();
  if (exists && (saved == EACCES || saved == EPERM || saved == EROFS) &&
      ::access(target.c_str(), W_OK) == 0) {
    // The folder takes no new file but the file is writable: the same rule for every output.
    if (kind == writer::stream)
      return true;  // written directly
    // A writer that needs a file name writes into the system's temporary folder, and commit()
    // copies the whole file into the target.
    temporary_ = temporary_pattern(error);
    if (temporary_.empty())
      return false;
    copy_into_target_ = true;
    if (create_temporary(temporary_))
      return true;
    temporary_.clear();
    error = std::strerror(errno);
    return false;
  }
  error = std::strerror(saved);
  return false;
}

bool output_file::commit(std::string& error) {
  if (temporary_.empty())
    return true;  // written directly, already closed by the caller
  bool ok = true;
  if (copy_into_target_) {
    file_handle in(std::fopen(temporary_.c_str(), "rb"), &std::fclose);
    file_handle out(std::fopen(target_.c_str(), "wb"), &std::fclose);
    ok = in && out;
    char buffer[1 << 16];
    while (ok) {
      const std::size_t n = std::fread(buffer, 1, sizeof buffer, in.get());
      if (n == 0)
        break;
      ok = std::fwrite(buffer, 1, n, out.get()) == n;
    }
    ok = ok && std::ferror(in.get()) == 0;
    if (out) {
      ok = std::fflush(out.get()) == 0 && ok;
      ok = std::fclose(out.release()) == 0 && ok;
    }
    if (!ok)
      error = std::strerror(errno);
  } else if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    ok = false;
    error = std::strerror(errno);
  } else {
    temporary_.clear();  // renamed: nothing left to remove
  }
  discard();
  return ok;
}

void output_file::remove_temporary() const {
  if (!temporary_.empty())
    ::unlink(temporary_.c_str());
}

void output_file::discard() {
  if (!temporary_.empty())
    ::unlink(temporary_.c_str());
  temporary_.clear();
}

}  // namespace clothlab
