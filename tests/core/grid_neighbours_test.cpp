// The neighbour table is written in C++ (src/core/grid_neighbours.hpp) and in GLSL
// (shaders/gpu_cloth_common.glsl, which the GPU paths' shaders include): both must list the same
// 12 neighbours in the same order, the order of the spring mask's bits.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/grid_neighbours.hpp"

namespace clothlab {
namespace {

// The file's text with its // comments removed.
std::string code_of(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return std::regex_replace(text.str(), std::regex("//[^\n]*"), "");
}

TEST(GridNeighbours, TheShadersTableIsTheCppOne) {
  const std::string path = std::string(CLOTHLAB_SOURCE_DIR) + "/shaders/gpu_cloth_common.glsl";
  const std::string code = code_of(path);
  ASSERT_FALSE(code.empty()) << path << " could not be read";

  std::smatch count;
  ASSERT_TRUE(std::regex_search(code, count,
                                std::regex(R"(const\s+int\s+neighbour_count\s*=\s*(\d+)\s*;)")))
      << path << ": no neighbour_count";
  EXPECT_EQ(std::stoi(count[1]), neighbour_count);

  std::smatch table;
  ASSERT_TRUE(std::regex_search(
      code, table,
      std::regex(
          R"(neighbours\s*\[\s*neighbour_count\s*\]\s*=\s*ivec3\s*\[\s*neighbour_count\s*\]\s*\(([^;]*)\)\s*;)")))
      << path << ": no neighbours[] table";
  std::vector<std::array<int, 3>> glsl;
  const std::string entries = table[1];
  const std::regex entry(R"(ivec3\s*\(\s*(-?\d+)\s*,\s*(-?\d+)\s*,\s*(-?\d+)\s*\))");
  for (auto it = std::sregex_iterator(entries.begin(), entries.end(), entry);
       it != std::sregex_iterator(); ++it) {
    glsl.push_back({std::stoi((*it)[1]), std::stoi((*it)[2]), std::stoi((*it)[3])});
  }
  ASSERT_EQ(glsl.size(), neighbour_offsets.size());
  for (std::size_t i = 0; i < glsl.size(); ++i) {
    EXPECT_EQ(glsl[i], neighbour_offsets[i])
        << "bit " << i << ": GLSL (" << glsl[i][0] << ", " << glsl[i][1] << ", " << glsl[i][2]
        << "), C++ (" << neighbour_offsets[i][0] << ", " << neighbour_offsets[i][1] << ", "
        << neighbour_offsets[i][2] << ")";
  }
}

// Each family's list (spring_mesh's order) holds the same neighbours as the spring mask's table;
// grid_neighbours.hpp also checks this when it compiles.
TEST(GridNeighbours, TheFamiliesListsHoldTheMasksNeighbours) {
  EXPECT_TRUE(neighbour_orders_agree());
}

}  // namespace
}  // namespace clothlab
