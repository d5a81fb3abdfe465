#include "app/png_output.hpp"

#include <string>

#include "app/run_control.hpp"
#include "core/i18n.hpp"
#include "gl/renderer.hpp"

namespace clothlab {
namespace {

// Renders the final state into the off-screen context with the stage's fixed camera and writes
// the PNG. `draw` receives the renderer and the view and draws the state.
template <class Draw>
int draw_png(const options& o, run_outputs& out, Draw&& draw) {
  std::string error;
  renderer scene_renderer;
  if (!scene_renderer.init(error)) {
    report("%s", error.c_str());
    return exit_failure;
  }
  draw(scene_renderer, camera::default_for(o.stage));
  if (!save_framebuffer_png(out.png_write_path(), o.width, o.height, error)) {
    report(tr("--png %s: %s"), o.png_path.c_str(), error.c_str());
    return exit_failure;
  }
  if (!out.check_png(error)) {
    report("%s", error.c_str());
    return exit_failure;
  }
  return 0;
}

template <class Stage>
int draw_stage_png(const options& o, run_outputs& out, const Stage& stage) {
  return draw_png(o, out, [&](renderer& r, const camera& view) {
    r.draw(stage, view, render_settings{}, o.width, o.height);
  });
}

}  // namespace

int write_png(const options& o, run_outputs& out, const single_spring& stage) {
  return draw_stage_png(o, out, stage);
}

int write_png(const options& o, run_outputs& out, const coupled_springs& stage) {
  return draw_stage_png(o, out, stage);
}

int write_png(const options& o, run_outputs& out, const spring_mesh& cloth) {
  return draw_stage_png(o, out, cloth);
}

int write_png(const options& o, run_outputs& out, cloth_paths& paths) {
  return draw_png(o, out, [&](renderer& r, const camera& view) {
    const cloth_textures textures = paths.textures();
    r.draw_from_textures(textures.position, textures.normal, paths.cloth, view, render_settings{},
                         o.width, o.height, 0, textures.spring_mask);
  });
}

}  // namespace clothlab
