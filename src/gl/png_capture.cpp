#include "gl/png_capture.hpp"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/i18n.hpp"
#include "gl/gl.hpp"

namespace clothlab {

bool framebuffer_png(int width, int height, std::vector<unsigned char>& png, std::string& error) {
  if (width < 1 || height < 1) {
    error = format(tr("cannot save a %dx%d image"), width, height);
    return false;
  }
  const auto row_bytes = static_cast<std::size_t>(width) * 4;
  std::vector<unsigned char> pixels(row_bytes * static_cast<std::size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  // GL's rows go bottom-up, PNG's top-down. The image is opaque whatever alpha blending left.
  std::vector<unsigned char> image(pixels.size());
  for (int y = 0; y < height; ++y) {
    const auto source = pixels.begin() + static_cast<std::ptrdiff_t>(row_bytes * (height - 1 - y));
    std::copy(source, source + static_cast<std::ptrdiff_t>(row_bytes),
              image.begin() + static_cast<std::ptrdiff_t>(row_bytes * y));
  }
  for (std::size_t i = 3; i < image.size(); i += 4)
    image[i] = 255;
  // stb's encoder hands the PNG over in pieces, appended to `png`.
  png.clear();
  const auto append = [](void* context, void* data, int size) {
    auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
    const auto* first = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), first, first + size);
  };
  if (stbi_write_png_to_func(append, &png, width, height, 4, image.data(),
                             static_cast<int>(row_bytes)) == 0) {
    error = tr("cannot encode the PNG image");
    return false;
  }
  return true;
}

bool save_framebuffer_png(const std::string& path, int width, int height, std::string& error) {
  std::vector<unsigned char> png;
  if (!framebuffer_png(width, height, png, error)) {
    error = path + colon() + error;
    return false;
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    error = path + colon() + tr("cannot write the PNG image");
    return false;
  }
  // Every write checked: a full disk must not leave a truncated PNG behind.
  const bool written = std::fwrite(png.data(), 1, png.size(), file) == png.size();
  if (std::fclose(file) != 0 || !written) {
    std::error_code ignored;
    if (std::filesystem::is_regular_file(path, ignored))  // never a device such as /dev/full
      std::filesystem::remove(path, ignored);
    error = path + colon() + tr("the PNG image could not be written whole (is the disk full?)");
    return false;
  }
  return true;
}

}  // namespace clothlab
