// RGBA8 images for the screenshot tests: read back from GL, loaded from and written to PNG,
// compared with a per-pixel tolerance.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace clothlab::image_testing {

struct rgba_image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // RGBA, top row first

  std::uint8_t channel(int x, int y, int c) const {
    return pixels[4 * (static_cast<std::size_t>(y) * width + x) + c];
  }
};

// The current framebuffer, top row first.
rgba_image read_framebuffer(int width, int height);
// Returns an empty image (width 0) when the file cannot be read.
rgba_image load_png(const std::filesystem::path& path);
bool write_png(const std::filesystem::path& path, const rgba_image& image);

// How two images of the same size differ. A pixel differs when one of its R, G, B channels
// differs by more than the tolerance (0..255).
struct image_difference {
  double differing_fraction = 1.0;  // of all pixels; 1 when the sizes differ
  int largest_channel_difference = 255;
};
image_difference compare_images(const rgba_image& actual, const rgba_image& expected,
                                int tolerance);
// Black where the pixels agree within the tolerance, the absolute difference (brightened)
// elsewhere.
rgba_image difference_image(const rgba_image& actual, const rgba_image& expected, int tolerance);

// The image moved right by dx and down by dy pixels, the uncovered border copied from the edge.
rgba_image shifted(const rgba_image& image, int dx, int dy);
// Number of distinct RGB colours.
std::size_t count_distinct_colours(const rgba_image& image);

}  // namespace clothlab::image_testing
