#include "window/state_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

unsigned char to_byte(double unit) {
  return static_cast<unsigned char>(std::lround(255.0 * std::clamp(unit, 0.0, 1.0)));
}

}  // namespace

state_images::~state_images() {
  glDeleteTextures(3, textures_.data());
}

void state_images::update(int grid_size, std::span<const double> positions,
                          std::span<const double> velocities, std::span<const double> normals) {
  const auto texels = static_cast<std::size_t>(grid_size) * static_cast<std::size_t>(grid_size);
  if (grid_size < 1 || positions.size() < 3 * texels || velocities.size() < 3 * texels ||
      normals.size() < 3 * texels)
    return;
  if (textures_[0] == 0) {
    glGenTextures(3, textures_.data());
    for (const GLuint texture : textures_) {
      glBindTexture(GL_TEXTURE_2D, texture);
      // One texel is one particle: square blocks when enlarged, no blending between particles.
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
  }
  grid_size_ = grid_size;
  const std::span<const double> sources[3] = {positions, velocities, normals};
  pixels_.resize(4 * texels);
  for (int image = 0; image < 3; ++image) {
    const std::span<const double> values = sources[image].first(3 * texels);
    values_[image].assign(values.begin(), values.end());
    std::array<double, 3> low = {values[0], values[1], values[2]};
    std::array<double, 3> high = low;
    double largest_speed = 0.0;
    for (std::size_t k = 0; k < texels; ++k) {
      for (std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], values[3 * k + c]);
        high[c] = std::max(high[c], values[3 * k + c]);
      }
      largest_speed =
          std::max(largest_speed, std::hypot(values[3 * k], values[3 * k + 1], values[3 * k + 2]));
    }
    for (std::size_t k = 0; k < texels; ++k) {
      for (std::size_t c = 0; c < 3; ++c) {
        const double x = values[3 * k + c];
        double unit = 0.5;
        if (image == position)
          unit = high[c] > low[c] ? (x - low[c]) / (high[c] - low[c]) : 0.5;
        else if (image == velocity)
          unit = largest_speed > 0.0 ? 0.5 + x / (2 * largest_speed) : 0.5;
        else
          unit = 0.5 + x / 2;
        pixels_[4 * k + c] = to_byte(unit);
      }
      pixels_[4 * k + 3] = 255;
    }
    char legend[256];
    if (image == position) {
      std::snprintf(legend, sizeof legend,
                    tr("rgb = xyz, each from its min to its max: x %.3g to %.3g, "
                       "y %.3g to %.3g, z %.3g to %.3g m"),
                    low[0], high[0], low[1], high[1], low[2], high[2]);
    } else if (image == velocity) {
      std::snprintf(legend, sizeof legend, tr("rgb = 0.5 + v / (2 |v|max), |v|max = %.3g m/s"),
                    largest_speed);
    } else {
      std::snprintf(legend, sizeof legend, "%s", tr("rgb = 0.5 + n / 2 (flat, up: lilac)"));
    }
    legends_[image] = legend;
    // Row kv of the image is particle row kv: texel (ku, kv) as on the GPU.
    glBindTexture(GL_TEXTURE_2D, textures_[image]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, grid_size, grid_size, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 pixels_.data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

std::array<double, 3> state_images::texel(which image, int ku, int kv) const {
  const std::vector<double>& values = values_[image];
  const auto k = static_cast<std::size_t>(ku + grid_size_ * kv);
  if (3 * k + 2 >= values.size())
    return {0.0, 0.0, 0.0};
  return {values[3 * k], values[3 * k + 1], values[3 * k + 2]};
}

}  // namespace clothlab
