// The off-screen implementation of gl_context: an OSMesa 3.3 core context rendering into a
// buffer in memory. Only compiled into the off-screen build of the GL code.
#include <GL/osmesa.h>

#include <vector>

#include "core/i18n.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"

namespace clothlab {
namespace {

class osmesa_context final : public gl_context {
 public:
  osmesa_context(OSMesaContext context, int width, int height)
      : context_(context),
        width_(width),
        height_(height),
        buffer_(static_cast<std::size_t>(width) * height * 4) {}
  ~osmesa_context() override { OSMesaDestroyContext(context_); }
  osmesa_context(const osmesa_context&) = delete;
  osmesa_context& operator=(const osmesa_context&) = delete;

  bool make_current() {
    return OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_) ==
           GL_TRUE;
  }
  int framebuffer_width() const override { return width_; }
  int framebuffer_height() const override { return height_; }
  std::string origin() const override { return tr("through OSMesa"); }

 private:
  OSMesaContext context_;
  int width_;
  int height_;
  std::vector<unsigned char> buffer_;  // RGBA8, bottom row first
};

}  // namespace

std::unique_ptr<gl_context> create_offscreen_context(int width, int height, std::string& error) {
  if (width < 1 || height < 1) {
    error =
        format(tr("off-screen buffer %dx%d: both sides must be at least 1 pixel"), width, height);
    return nullptr;
  }
  // 4.3 core (compute shaders) where Mesa has it, else 3.3 core.
  OSMesaContext context = nullptr;
  for (const int version : {43, 33}) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              version / 10,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              version % 10,
                              0};
    context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context != nullptr)
      break;
  }
  if (context == nullptr) {
    error = tr("OSMesa could not create an OpenGL 3.3 core context");
    return nullptr;
  }
  auto result = std::make_unique<osmesa_context>(context, width, height);
  if (!result->make_current()) {
    error = tr("OSMesa could not make its context current");
    return nullptr;
  }
  OSMesaPixelStore(OSMESA_Y_UP, 1);
  return result;
}

}  // namespace clothlab
