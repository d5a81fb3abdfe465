#include "image.hpp"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <unordered_set>

#include "gl/gl.hpp"

namespace clothlab::image_testing {

rgba_image read_framebuffer(int width, int height) {
  rgba_image image{width, height, {}};
  const auto row_bytes = 4 * static_cast<std::size_t>(width);
  std::vector<std::uint8_t> bottom_up(row_bytes * static_cast<std::size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  image.pixels.resize(bottom_up.size());
  for (int y = 0; y < height; ++y) {
    std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(row_bytes * (height - 1 - y)),
                row_bytes, image.pixels.begin() + static_cast<std::ptrdiff_t>(row_bytes * y));
  }
  for (std::size_t i = 3; i < image.pixels.size(); i += 4)
    image.pixels[i] = 255;
  return image;
}

rgba_image load_png(const std::filesystem::path& path) {
  int width = 0;
  int height = 0;
  int channels = 0;
  stbi_uc* data = stbi_load(path.string().c_str(), &width, &height, &channels, 4);
  if (data == nullptr)
    return {};
  rgba_image image{width, height, {}};
  image.pixels.assign(data, data + 4 * static_cast<std::size_t>(width) * height);
  stbi_image_free(data);
  return image;
}

bool write_png(const std::filesystem::path& path, const rgba_image& image) {
  std::error_code ignored;
  std::filesystem::create_directories(path.parent_path(), ignored);
  return stbi_write_png(path.string().c_str(), image.width, image.height, 4, image.pixels.data(),
                        4 * image.width) != 0;
}

namespace {

int largest_rgb_difference(const rgba_image& a, const rgba_image& b, std::size_t pixel) {
  int largest = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    largest = std::max(largest, std::abs(int{a.pixels[4 * pixel + c]} - b.pixels[4 * pixel + c]));
  }
  return largest;
}

bool same_size(const rgba_image& a, const rgba_image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         !a.pixels.empty();
}

}  // namespace

image_difference compare_images(const rgba_image& actual, const rgba_image& expected,
                                int tolerance) {
  if (!same_size(actual, expected))
    return {};
  const std::size_t count = actual.pixels.size() / 4;
  std::size_t differing = 0;
  int largest = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const int d = largest_rgb_difference(actual, expected, i);
    largest = std::max(largest, d);
    if (d > tolerance)
      ++differing;
  }
  return {static_cast<double>(differing) / static_cast<double>(count), largest};
}

rgba_image difference_image(const rgba_image& actual, const rgba_image& expected, int tolerance) {
  if (!same_size(actual, expected))
    return actual;
  rgba_image result = actual;
  for (std::size_t i = 0; i < actual.pixels.size() / 4; ++i) {
    const bool differs = largest_rgb_difference(actual, expected, i) > tolerance;
    for (std::size_t c = 0; c < 3; ++c) {
      const int d = std::abs(int{actual.pixels[4 * i + c]} - expected.pixels[4 * i + c]);
      result.pixels[4 * i + c] = differs ? static_cast<std::uint8_t>(std::min(255, 64 + 4 * d)) : 0;
    }
    result.pixels[4 * i + 3] = 255;
  }
  return result;
}

rgba_image shifted(const rgba_image& image, int dx, int dy) {
  rgba_image result = image;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int source_x = std::clamp(x - dx, 0, image.width - 1);
      const int source_y = std::clamp(y - dy, 0, image.height - 1);
      for (int c = 0; c < 4; ++c) {
        result.pixels[4 * (static_cast<std::size_t>(y) * image.width + x) + c] =
            image.channel(source_x, source_y, c);
      }
    }
  }
  return result;
}

std::size_t count_distinct_colours(const rgba_image& image) {
  std::unordered_set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
    colours.insert(std::uint32_t{image.pixels[i]} << 16 | std::uint32_t{image.pixels[i + 1]} << 8 |
                   image.pixels[i + 2]);
  }
  return colours.size();
}

}  // namespace clothlab::image_testing
