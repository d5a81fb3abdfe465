#include "app/data_files.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <utility>
#include <vector>

#include "core/i18n.hpp"
#include "gl/shader.hpp"  // shader_path, asset_path

namespace clothlab {

bool data_files_present(const options& o, std::string& error) {
  std::vector<std::pair<std::string, std::string>> needed;  // (option, file)
  const auto shaders = [&](const std::string& option, std::initializer_list<const char*> names) {
    for (const char* name : names)
      needed.emplace_back(option, shader_path(name).string());
  };
  if (o.stage == stage_kind::cloth && o.backend == cloth_backend::gpu) {
    shaders("--backend gpu", {"gpu_full_screen.vert", "gpu_step.frag", "gpu_cloth_common.glsl",
                              "gpu_normal.frag", "gpu_tear.frag", "gpu_check.frag"});
  }
  if (o.stage == stage_kind::cloth && o.backend == cloth_backend::gpu_compute) {
    shaders("--backend gpu-compute",
            {"gpu_compute_step.comp", "gpu_cloth_common.glsl", "gpu_compute_normal.comp",
             "gpu_compute_tear.comp", "gpu_xpbd_predict.comp", "gpu_xpbd_solve.comp",
             "gpu_xpbd_velocity.comp"});
  }
  if (!o.png_path.empty()) {
    const std::string option = "--png " + o.png_path;
    shaders(option,
            {"draw_background.vert", "draw_background.frag", "draw_ground.vert", "draw_ground.frag",
             "draw_flat.vert", "draw_flat.frag", "draw_cloth.vert", "draw_lit.frag",
             "draw_cloth_from_textures.vert", "draw_flat_from_texture.vert", "draw_spheres.vert",
             "draw_blob_shadow.vert", "draw_blob_shadow.frag"});
    needed.emplace_back(option, asset_path("cloth.png").string());
  }
  for (const auto& [option, file] : needed) {
    if (std::ifstream(file).good())
      continue;
    error = option + colon() +
            format(tr("cannot read %s: %s (the data folder: CLOTHLAB_DATA_DIR, or the one found "
                      "beside the program)"),
                   file.c_str(), std::strerror(errno));
    // The student copy has no compute path: its step shader would answer questions 6, 9, 12 and
    // 13 (docs/teaching.md).
    if (file.ends_with("gpu_compute_step.comp"))
      error += tr("; a student copy of the lab has no compute path: it is in the teacher's copy");
    return false;
  }
  return true;
}

}  // namespace clothlab
