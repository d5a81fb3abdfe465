// The EGL implementation of the off-screen gl_context: an OpenGL core context on an
// EGL device (a real GPU through its driver, or Mesa's software device), or on Mesa's
// surfaceless platform when the driver lists no device, rendering into a pbuffer of the given
// size. Only compiled into the EGL build of the GL code (clothlab-egl), linked with glvnd's
// libEGL and libOpenGL: the gl* calls go to whichever vendor the context belongs to.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/i18n.hpp"
#include "gl/gl.hpp"
#include "gl/gl_context.hpp"

namespace clothlab {
namespace {

class egl_context final : public gl_context {
 public:
  egl_context(EGLDisplay display, EGLContext context, EGLSurface surface, int width, int height,
              std::string origin)
      : display_(display),
        context_(context),
        surface_(surface),
        width_(width),
        height_(height),
        origin_(std::move(origin)) {}
  ~egl_context() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  egl_context(const egl_context&) = delete;
  egl_context& operator=(const egl_context&) = delete;

  int framebuffer_width() const override { return width_; }
  int framebuffer_height() const override { return height_; }
  std::string origin() const override { return origin_; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  EGLSurface surface_;
  int width_;
  int height_;
  std::string origin_;  // "through EGL (...)": the device or platform open_display found
};

bool has_extension(const char* extensions, const char* name) {
  if (extensions == nullptr)
    return false;
  const std::size_t length = std::strlen(name);
  for (const char* at = std::strstr(extensions, name); at != nullptr;
       at = std::strstr(at + length, name)) {
    if ((at == extensions || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0'))
      return true;
  }
  return false;
}

// Mesa's software device says so by an extension; a GPU's driver does not.
bool is_software(EGLDeviceEXT device) {
  const auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  const char* extensions =
      query_device_string ? query_device_string(device, EGL_EXTENSIONS) : nullptr;
  return has_extension(extensions, "EGL_MESA_device_software");
}

// The devices EGL knows, hardware ones first (Mesa's software device says so by an extension).
std::vector<EGLDeviceEXT> devices_hardware_first() {
  const auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (query_devices == nullptr)
    return {};
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0)
    return {};
  std::vector<EGLDeviceEXT> all(static_cast<std::size_t>(count));
  query_devices(count, all.data(), &count);
  std::vector<EGLDeviceEXT> hardware, software;
  for (EGLDeviceEXT device : all)
    (is_software(device) ? software : hardware).push_back(device);
  hardware.insert(hardware.end(), software.begin(), software.end());
  return hardware;
}

// An initialised display: the first device that initialises, else the surfaceless platform;
// `origin` says which.
EGLDisplay open_display(std::string& origin) {
  const auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (platform_display == nullptr)
    return EGL_NO_DISPLAY;
  for (EGLDeviceEXT device : devices_hardware_first()) {
    EGLDisplay display = platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) {
      origin = is_software(device) ? tr("through EGL (Mesa's software device)")
                                   : tr("through EGL (a hardware device)");
      return display;
    }
  }
  origin = tr("through EGL (Mesa's surfaceless platform)");
  EGLDisplay display =
      platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr))
    return display;
  return EGL_NO_DISPLAY;
}

}  // namespace

bool egl_hardware_device_available() {
  for (EGLDeviceEXT device : devices_hardware_first()) {
    if (!is_software(device))
      return true;
  }
  return false;
}

std::unique_ptr<gl_context> create_offscreen_context(int width, int height, std::string& error) {
  if (width < 1 || height < 1) {
    error =
        format(tr("off-screen buffer %dx%d: both sides must be at least 1 pixel"), width, height);
    return nullptr;
  }
  std::string origin;
  EGLDisplay display = open_display(origin);
  if (display == EGL_NO_DISPLAY) {
    error = tr("EGL found no device and no surfaceless platform to render on");
    return nullptr;
  }
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_ALPHA_SIZE,
                                      8,
                                      EGL_DEPTH_SIZE,
                                      24,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1) {
    eglTerminate(display);
    error = tr("EGL has no RGBA8 pbuffer configuration for OpenGL");
    return nullptr;
  }
  const EGLint surface_attributes[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
  EGLSurface surface = eglCreatePbufferSurface(display, config, surface_attributes);
  if (surface == EGL_NO_SURFACE || !eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    error = format(tr("EGL could not create a %dx%d pbuffer for OpenGL"), width, height);
    return nullptr;
  }
  // 4.3 core (compute shaders) where the driver has it, else 3.3 core.
  EGLContext context = EGL_NO_CONTEXT;
  for (const EGLint minor_major : {43, 33}) {
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         minor_major / 10,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         minor_major % 10,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context != EGL_NO_CONTEXT)
      break;
  }
  if (context == EGL_NO_CONTEXT) {
    eglDestroySurface(display, surface);
    eglTerminate(display);
    error = tr("EGL could not create an OpenGL 3.3 core context");
    return nullptr;
  }
  auto result =
      std::make_unique<egl_context>(display, context, surface, width, height, std::move(origin));
  if (!eglMakeCurrent(display, surface, surface, context)) {
    error = tr("EGL could not make its context current");
    return nullptr;
  }
  return result;
}

}  // namespace clothlab
