// The particle arrays (layout 3k + c, finiteness check) and the CSV and OBJ writers of cli.md.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/export.hpp"
#include "core/particle_system.hpp"
#include "core/spring_mesh.hpp"

namespace clothlab {
namespace {

TEST(ParticleSystem, ResizeGivesParticlesAtTheOriginAtRestNotFixed) {
  particle_system particles;
  particles.resize(4);
  EXPECT_EQ(particles.size(), 4u);
  EXPECT_EQ(particles.position, std::vector<double>(12, 0.0));
  EXPECT_EQ(particles.velocity, std::vector<double>(12, 0.0));
  EXPECT_EQ(particles.force.size(), 12u);
  EXPECT_EQ(particles.is_fixed, std::vector<std::uint8_t>(4, 0));
}

TEST(ParticleSystem, SettersUseTheFlatLayoutThreeKPlusC) {
  particle_system particles;
  particles.resize(3);
  particles.set_position(2, {1.0, 2.0, 3.0});
  particles.set_velocity(1, {-4.0, -5.0, -6.0});
  EXPECT_EQ(particles.position[6], 1.0);
  EXPECT_EQ(particles.position[7], 2.0);
  EXPECT_EQ(particles.position[8], 3.0);
  EXPECT_EQ(particles.velocity[3], -4.0);
  EXPECT_EQ(particles.velocity[4], -5.0);
  EXPECT_EQ(particles.velocity[5], -6.0);
  EXPECT_EQ(particles.get_position(2), glm::dvec3(1.0, 2.0, 3.0));
}

TEST(ParticleSystem, IsFiniteDetectsNaNAndInfinity) {
  particle_system particles;
  particles.resize(3);
  particles.set_position(1, {1e300, -1e300, 0.5});
  EXPECT_TRUE(particles.is_finite());
  particles.position[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(particles.is_finite());
  particles.position[4] = 0.0;
  particles.velocity[8] = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(particles.is_finite());
  particles.velocity[8] = 0.0;
  particles.velocity[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(particles.is_finite());
  particles.velocity[0] = 0.0;
  EXPECT_TRUE(particles.is_finite());
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, separator)) {
    fields.push_back(field);
  }
  return fields;
}

std::string read_all(std::FILE* file) {
  std::rewind(file);
  std::string text;
  char buffer[4096];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file)) > 0) {
    text.append(buffer, count);
  }
  return text;
}

// The header is exactly the one of cli.md, then one line per particle in index order:
// step, t, particle, x, y, z, vx, vy, vz, the numbers reading back to the very same doubles.
TEST(CsvExport, HeaderAndLinesReadBackToTheSameDoubles) {
  particle_system particles;
  particles.resize(3);
  particles.set_position(0, {0.1, 1.0 / 3.0, -2.5e-300});
  particles.set_velocity(0, {1e300, -0.0, 2.0 / 7.0});
  particles.set_position(1, {std::sqrt(2.0), -1e-17, 123456789.123456789});
  particles.set_velocity(1, {0.30000000000000004, 5e-324, -1.0});
  particles.set_position(2, {-0.5, 0.5, 0.0});

  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  write_csv_header(file);
  write_csv_step(file, 7, 0.07, particles);
  const std::string text = read_all(file);
  std::fclose(file);

  const std::vector<std::string> lines = split(text, '\n');
  ASSERT_EQ(lines.size(), 4u) << text;
  EXPECT_EQ(lines[0], "step,t,particle,x,y,z,vx,vy,vz");
  for (std::size_t k = 0; k < 3; ++k) {
    const std::vector<std::string> fields = split(lines[k + 1], ',');
    ASSERT_EQ(fields.size(), 9u) << lines[k + 1];
    EXPECT_EQ(fields[0], "7");
    EXPECT_EQ(std::strtod(fields[1].c_str(), nullptr), 0.07);
    EXPECT_EQ(fields[2], std::to_string(k));
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(std::strtod(fields[3 + c].c_str(), nullptr), particles.position[3 * k + c])
          << "particle " << k << ", " << fields[3 + c];
      EXPECT_EQ(std::strtod(fields[6 + c].c_str(), nullptr), particles.velocity[3 * k + c])
          << "particle " << k << ", " << fields[6 + c];
    }
  }
}

class scratch_directory {
 public:
  scratch_directory() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "clothlab-core-XXXXXX").string();
    if (mkdtemp(pattern.data()) != nullptr) {
      path_ = pattern;
    }
  }
  ~scratch_directory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  scratch_directory(const scratch_directory&) = delete;
  scratch_directory& operator=(const scratch_directory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// N x N cloth: N^2 positions, normals and texture coordinates, 2 (N-1)^2 triangles whose
// vertex indices (1-based) are all within the N^2 vertices.
TEST(ObjExport, ClothObjHasOneVertexPerParticleAndTwoTrianglesPerCell) {
  constexpr int n = 6;
  cloth_parameters parameters;
  parameters.grid_size = n;
  spring_mesh cloth(parameters);
  cloth.load_model();
  for (int s = 0; s < 20; ++s) {
    cloth.step();
  }
  cloth.compute_normals();
  const scratch_directory directory;
  ASSERT_FALSE(directory.path().empty());
  const std::string path = (directory.path() / "cloth.obj").string();
  ASSERT_TRUE(write_obj(path, n, cloth.particles(), cloth.normals()));

  std::ifstream obj(path);
  std::string line;
  int positions = 0;
  int normals = 0;
  int texture_coordinates = 0;
  int triangles = 0;
  while (std::getline(obj, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      double x = 0, y = 0, z = 0;
      ASSERT_TRUE(fields >> x >> y >> z) << line;
      EXPECT_NEAR(x, cloth.particles().position[3 * static_cast<std::size_t>(positions)], 1e-6)
          << line;
      ++positions;
    } else if (tag == "vn") {
      double x = 0, y = 0, z = 0;
      ASSERT_TRUE(fields >> x >> y >> z) << line;
      EXPECT_NEAR(x * x + y * y + z * z, 1.0, 1e-9) << line;
      ++normals;
    } else if (tag == "vt") {
      double u = -1, v = -1;
      ASSERT_TRUE(fields >> u >> v) << line;
      EXPECT_TRUE(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0) << line;
      ++texture_coordinates;
    } else if (tag == "f") {
      std::string corner;
      int corners = 0;
      while (fields >> corner) {
        for (const std::string& index : split(corner, '/')) {
          if (index.empty()) {
            continue;  // "v//vn"
          }
          const long value = std::strtol(index.c_str(), nullptr, 10);
          EXPECT_TRUE(value >= 1 && value <= n * n) << line;
        }
        ++corners;
      }
      EXPECT_EQ(corners, 3) << line;
      ++triangles;
    }
  }
  EXPECT_EQ(positions, n * n);
  EXPECT_EQ(normals, n * n);
  EXPECT_EQ(texture_coordinates, n * n);
  EXPECT_EQ(triangles, 2 * (n - 1) * (n - 1));
}

TEST(ObjExport, UnwritablePathReturnsFalse) {
  cloth_parameters parameters;
  parameters.grid_size = 3;
  spring_mesh cloth(parameters);
  cloth.load_model();
  cloth.compute_normals();
  EXPECT_FALSE(
      write_obj("/nonexistent-clothlab-dir/cloth.obj", 3, cloth.particles(), cloth.normals()));
}

}  // namespace
}  // namespace clothlab
