// clothlab in a browser: the platform file of the window (window_app.hpp) for the WebAssembly
// build (web/CMakeLists.txt). The page (web/index.html) gives it a canvas; it makes a WebGL2
// context there through emscripten's GLFW, starts window_app with the defaults of docs/cli.md,
// and runs one frame per animation frame of the page. What the desktop has and the browser has
// not (docs/web.md): the command line, files (P downloads the screenshot), threads (the
// cpu-parallel path and the stability map's worker threads), compute shaders.
#include <backends/imgui_impl_glfw.h>
#include <emscripten.h>
#include <emscripten/html5.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "gl/gl.hpp"

#include <GLFW/glfw3.h>

#include "app/options.hpp"
#include "core/i18n.hpp"
#include "core/spring_mesh.hpp"
#include "gl/renderer.hpp"
#include "window/glfw_context.hpp"
#include "window/window_app.hpp"

namespace clothlab {
namespace {

// The page: the context and the program, for the lifetime of the page (main returns; the
// browser calls frame() at each animation frame).
struct web_page {
  std::unique_ptr<glfw_context> context;
  std::unique_ptr<window_app> app;
};
web_page page;

// clang-format off
// What the page shows under the canvas (text, in the user's language) and what the browser test
// reads (window.clothlab.status): the stage, the cloth's path and size, the simulated time, the
// steps and their rate, the frame rate, the language.
EM_JS(void, set_page_status, (const char* stage, const char* backend, int grid_size, double time,
                              double steps, double steps_per_second, double frames_per_second,
                              int diverged, const char* language, const char* text), {
  const page = window.clothlab || (window.clothlab = {});
  page.status = {
    stage: UTF8ToString(stage), backend: UTF8ToString(backend), grid_size: grid_size,
    time: time, steps: steps, steps_per_second: steps_per_second,
    frames_per_second: frames_per_second, diverged: diverged != 0,
    language: UTF8ToString(language), text: UTF8ToString(text)
  };
  document.documentElement.lang = page.status.language;
  if (page.onstatus) page.onstatus(page.status);
});

// The language the page asks for: ?lang=fr in its address, else the browser's (navigator.language,
// "fr-FR"), into `out` (at most `size` bytes).
EM_JS(void, page_language, (char* out, int size), {
  const asked = new URLSearchParams(window.location.search).get('lang') || navigator.language || "";
  stringToUTF8(asked, out, size);
});
// clang-format on

// The stage as the status bar names it.
const char* stage_word(stage_kind stage) {
  switch (stage) {
    case stage_kind::spring:
      return tr("spring");
    case stage_kind::coupled:
      return tr("chain");
    case stage_kind::cloth:
      break;
  }
  return tr("cloth");
}

void publish_status(const scene& the_scene) {
  const std::string stage(stage_name(the_scene.stage()));
  const run_status& status = the_scene.status();
  const std::string text =
      format(tr("clothlab · stage %s · cloth on the %s (N = %d) · t = %.2f s · %.0f steps/s · "
                "%.0f frames/s%s · H: the keys"),
             stage_word(the_scene.stage()), tr(backend_name(the_scene.backend())),
             the_scene.cloth_stage.parameters.grid_size, status.time, the_scene.steps_per_second(),
             the_scene.frames_per_second(), status.diverged ? tr(" · diverged") : "");
  set_page_status(stage.c_str(), backend_option(the_scene.backend()),
                  the_scene.cloth_stage.parameters.grid_size, status.time,
                  static_cast<double>(the_scene.steps_taken()), the_scene.steps_per_second(),
                  the_scene.frames_per_second(), status.diverged ? 1 : 0,
                  std::string(current_language()).c_str(), text.c_str());
}

// The browser's wheel deltas are pixels (about 100 a notch in Chromium; lines, 3 a notch, in
// Firefox), positive rightwards and downwards. GLFW's are notches, positive leftwards and away
// from the user, as the panel (Dear ImGui) and the zoom expect. emscripten's GLFW hands on the
// horizontal delta as the browser gives it, and the vertical one too before emscripten 3.1.8
// (Debian 12 has 3.1.6); from 3.1.8 on (Debian 13 has 3.1.69) the vertical one comes already
// in notches, at least one per event. Installed after Dear ImGui's callback, this converts
// what is still the browser's, then calls it (which calls the window's own).
#if !defined(__EMSCRIPTEN_major__) || !defined(__EMSCRIPTEN_minor__) || \
    !defined(__EMSCRIPTEN_tiny__)
#error "emscripten's version is unknown (emscripten.h defines __EMSCRIPTEN_major__ and the others)"
#endif
constexpr bool glfw_vertical_wheel_in_notches =
    __EMSCRIPTEN_major__ > 3 ||
    (__EMSCRIPTEN_major__ == 3 &&
     (__EMSCRIPTEN_minor__ > 1 || (__EMSCRIPTEN_minor__ == 1 && __EMSCRIPTEN_tiny__ >= 8)));

double browser_delta_to_notches(double delta) {
  return -(std::abs(delta) >= 10.0 ? delta / 100.0 : delta / 3.0);
}

void on_browser_wheel(GLFWwindow* window, double x, double y) {
  ImGui_ImplGlfw_ScrollCallback(window, browser_delta_to_notches(x),
                                glfw_vertical_wheel_in_notches ? y : browser_delta_to_notches(y));
}

// From 1.89.3 on, Dear ImGui's GLFW backend ignores GLFW's wheel in a browser and takes the
// panel's from a wheel listener on the document (emscripten's html5 API) that cancels each event
// (Debian 13's 1.90): browsers treat a document's wheel listeners as passive, so Chromium ignores
// the cancel and logs a console error at every notch. This listener takes its place: the same
// deltas in notches (a line is a third of a notch, a pixel a hundredth, a page 80), and it
// cancels nothing: GLFW's listener on the canvas already keeps the page from scrolling under the
// window. (tests/web checks that the wheel scrolls the panel and that the console stays clean.)
#if IMGUI_VERSION_NUM >= 18930
float dom_delta_to_notches(double delta, unsigned long mode) {
  const double per_unit = mode == DOM_DELTA_LINE ? 1.0 / 3.0 : mode == DOM_DELTA_PAGE ? 80.0 : 0.01;
  return static_cast<float>(-delta * per_unit);
}

EM_BOOL on_document_wheel(int /*event_type*/, const EmscriptenWheelEvent* event, void*) {
  ImGui::GetIO().AddMouseWheelEvent(dom_delta_to_notches(event->deltaX, event->deltaMode),
                                    dom_delta_to_notches(event->deltaY, event->deltaMode));
  return EM_FALSE;
}
#endif

void frame(void* /*unused*/) {
  page.app->frame(page.context->poll_events());
  publish_status(page.app->the_scene());
}

// clang-format off
// Hands `size` bytes of PNG to the browser as a download named `name`, and notes it in
// window.clothlab.downloads (the browser test reads the image back from its address).
EM_JS(void, download_png, (const unsigned char* bytes, int size, const char* name), {
  const blob = new Blob([HEAPU8.slice(bytes, bytes + size)], {type: 'image/png'});
  const link = document.createElement('a');
  link.href = URL.createObjectURL(blob);
  link.download = UTF8ToString(name);
  document.body.appendChild(link);
  link.click();
  link.remove();
  const page = window.clothlab || (window.clothlab = {});
  (page.downloads || (page.downloads = [])).push({name: link.download, url: link.href, size: size});
  setTimeout(() => URL.revokeObjectURL(link.href), 60000);
});
// clang-format on

}  // namespace

void deliver_screenshot(stage_kind stage, int width, int height) {
  std::vector<unsigned char> png;
  std::string error;
  if (!framebuffer_png(width, height, png, error)) {
    std::fprintf(stderr, tr("clothlab: screenshot failed: %s\n"), error.c_str());
    return;
  }
  const std::string name = "clothlab-" + std::string(stage_name(stage)) + ".png";
  download_png(png.data(), static_cast<int>(png.size()), name.c_str());
  std::printf(tr("clothlab: screenshot %s downloaded (%d x %d)\n"), name.c_str(), width, height);
}

}  // namespace clothlab

extern "C" {

// The page calls it when the browser window changes size: the canvas takes the new size.
EMSCRIPTEN_KEEPALIVE void clothlab_resize(int width, int height) {
  if (clothlab::page.context)
    glfwSetWindowSize(clothlab::page.context->window(), std::max(width, 1), std::max(height, 1));
}

// scripts/benchmark-web: steps/s of the readable CPU path (spring_mesh::step, as the native
// benchmark step/cpu/N) on the default cloth of N x N particles, stepped for about `seconds` of
// wall-clock time between two frames of the page.
EMSCRIPTEN_KEEPALIVE double clothlab_cpu_steps_per_second(int n, double seconds) {
  clothlab::cloth_parameters p;
  p.grid_size = std::clamp(n, 2, 512);
  clothlab::spring_mesh cloth(p);
  // At most a minute: the page does nothing else meanwhile.
  seconds = std::isfinite(seconds) ? std::clamp(seconds, 0.0, 60.0) : 0.0;
  const double start = emscripten_get_now();  // ms
  long steps = 0;
  double elapsed = 0.0;
  do {
    for (int i = 0; i < 10; ++i)
      cloth.step();
    steps += 10;
    elapsed = (emscripten_get_now() - start) / 1000.0;
  } while (elapsed < seconds);
  return static_cast<double>(steps) / elapsed;
}

}  // extern "C"

int main() {
  using namespace clothlab;
  // The page's language (?lang=, else the browser's; English for one clothlab does not speak).
  start_messages();
  char asked[64] = "";
  page_language(asked, sizeof asked);
  set_language(language_of_locale(asked));
  const options start;  // the defaults of docs/cli.md: the cloth, on the CPU
  double css_width = 1280.0, css_height = 800.0;
  emscripten_get_element_css_size("#canvas", &css_width, &css_height);
  std::string error;
  page.context = glfw_context::create("clothlab", std::max(static_cast<int>(css_width), 320),
                                      std::max(static_cast<int>(css_height), 240), error);
  if (!page.context) {
    std::fprintf(stderr, tr("clothlab: %s\n"), error.c_str());
    return 1;
  }
  // Float colour attachments (the GPU cloth's state textures) are an extension in WebGL2; without
  // it the GPU path says why it cannot run (gpu_cloth), and the CPU path runs as before.
  if (!emscripten_webgl_enable_extension(emscripten_webgl_get_current_context(),
                                         "EXT_color_buffer_float"))
    std::printf("%s\n", tr("clothlab: this browser has no EXT_color_buffer_float: no GPU cloth "
                           "path"));
  std::printf("clothlab: %s, %s\n", page.context->description().c_str(),
              page.context->origin().c_str());
  page.app = window_app::create(*page.context, start, error);
  if (!page.app) {
    std::fprintf(stderr, tr("clothlab: %s\n"), error.c_str());
    return 1;
  }
  glfwSetScrollCallback(page.context->window(), on_browser_wheel);
#if IMGUI_VERSION_NUM >= 18930
  // (A registration adds a listener: Dear ImGui's is removed first.)
  emscripten_set_wheel_callback(EMSCRIPTEN_EVENT_TARGET_DOCUMENT, nullptr, false, nullptr);
  emscripten_set_wheel_callback(EMSCRIPTEN_EVENT_TARGET_DOCUMENT, nullptr, false,
                                on_document_wheel);
#endif
  // One frame per animation frame of the page; main returns and the page lives on.
  emscripten_set_main_loop_arg(frame, nullptr, 0, false);
  return 0;
}
