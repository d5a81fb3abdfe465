// Question 11, seen: the cloth's position, velocity and normal "textures" as small false-colour
// images, texel (ku, kv) = particle k = ku + N kv, as the GPU path stores them (gpu_cloth.hpp).
// On the GPU path they are read back from the GPU (positions and velocities with the frame's
// read-back, normals from the normal texture); on the CPU path they are made from the CPU's
// arrays, laid out the same way. Display only.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "gl/gl.hpp"

namespace clothlab {

class state_images {
 public:
  enum which { position = 0, velocity = 1, normal = 2 };

  state_images() = default;
  ~state_images();
  state_images(const state_images&) = delete;
  state_images& operator=(const state_images&) = delete;

  // Makes the three N x N images from the state (3 doubles per particle, particle k = ku + N kv):
  // position: each coordinate from its smallest to its largest value over the cloth (0..1);
  // velocity: 0.5 + v / (2 max |v|), grey at rest; normal: 0.5 + n / 2, the usual normal map.
  void update(int grid_size, std::span<const double> positions, std::span<const double> velocities,
              std::span<const double> normals);

  GLuint texture(which image) const { return textures_[image]; }
  int grid_size() const { return grid_size_; }
  // What the colours mean for each image, e.g. "x, y, z from (-0.5, -0.5, -1) to (0.5, ...) m".
  const std::string& legend(which image) const { return legends_[image]; }
  // The value of one texel (xyz), for the tooltip.
  std::array<double, 3> texel(which image, int ku, int kv) const;

 private:
  std::array<GLuint, 3> textures_{};
  std::array<std::string, 3> legends_;
  std::array<std::vector<double>, 3> values_;  // the last state, 3 doubles per texel
  std::vector<unsigned char> pixels_;          // RGBA8 scratch
  int grid_size_ = 0;
};

}  // namespace clothlab
