// The neighbours s(ku + du, kv + dv) that a spring can join to the vertex s(ku, kv) of the cloth
// (handout, figure 6), written once for the C++ code: the readable CPU cloth (spring_mesh), the
// parallel CPU path (cloth_parallel) and the GPU paths' spring masks (gpu_step_inputs). Two
// orders of the same twelve, each for its own reason, checked below to hold the same neighbours:
// each family's, in which spring_mesh::compute_force sums the forces, and the spring mask's bits.
// The shaders' neighbours[] (shaders/gpu_cloth_common.glsl) is neighbour_offsets in GLSL:
// tests/core/grid_neighbours_test.cpp checks that the two are equal.
#pragma once

#include <array>
#include <cstddef>

#include "core/spring_family.hpp"

namespace clothlab {

struct grid_offset {
  int du;
  int dv;
};

// Each family's four neighbours, in the order compute_force visits them: the order in which a
// vertex's spring forces are summed (cloth_parallel sums them in the same order, so that both
// paths round alike).
inline constexpr std::array<grid_offset, 4> structural_neighbours = {
    {{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};  // rest length h
inline constexpr std::array<grid_offset, 4> shear_neighbours = {
    {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}}};  // h√2
inline constexpr std::array<grid_offset, 4> bending_neighbours = {
    {{2, 0}, {0, 2}, {-2, 0}, {0, -2}}};  // 2h

constexpr const std::array<grid_offset, 4>& family_neighbours(spring_family family) {
  switch (family) {
    case spring_family::structural:
      return structural_neighbours;
    case spring_family::shear:
      return shear_neighbours;
    case spring_family::bending:
      break;
  }
  return bending_neighbours;
}

// The 12 neighbours in the order of the spring mask's bits (bit i: the spring to
// neighbour_offsets[i]) and of the shaders' neighbours[]: (du, dv, family), family 0 structural,
// 1 shear, 2 bending.
inline constexpr int neighbour_count = 12;
inline constexpr std::array<std::array<int, 3>, neighbour_count> neighbour_offsets = {
    {{1, 0, 0},
     {-1, 0, 0},
     {0, 1, 0},
     {0, -1, 0},  // structural
     {1, 1, 1},
     {-1, -1, 1},
     {1, -1, 1},
     {-1, 1, 1},  // shear
     {2, 0, 2},
     {-2, 0, 2},
     {0, 2, 2},
     {0, -2, 2}}};  // bending

// True when neighbour_offsets holds each family's neighbours exactly once, with its family.
constexpr bool neighbour_orders_agree() {
  std::size_t listed = 0;
  for (const spring_family family : all_spring_families) {
    for (const grid_offset o : family_neighbours(family)) {
      int found = 0;
      for (const auto& [du, dv, f] : neighbour_offsets)
        found += du == o.du && dv == o.dv && f == static_cast<int>(family) ? 1 : 0;
      if (found != 1)
        return false;
      ++listed;
    }
  }
  return listed == neighbour_offsets.size();
}
static_assert(neighbour_orders_agree(),
              "grid_neighbours.hpp: the spring mask's order and the families' lists differ");

}  // namespace clothlab
