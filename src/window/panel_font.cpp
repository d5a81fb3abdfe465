#include "window/panel_font.hpp"

#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

// Where the font may be, first found first: $CLOTHLAB_DATA_DIR/fonts (the page packs it at
// /clothlab/fonts), the file CMake found (CLOTHLAB_FONT_FILE), then where Linux distributions put
// DejaVu Sans, then macOS's own font with the same letters (Arial Unicode, part of macOS).
std::vector<std::filesystem::path> font_candidates() {
  std::vector<std::filesystem::path> candidates;
  if (const char* data = std::getenv("CLOTHLAB_DATA_DIR"); data != nullptr && *data != '\0')
    candidates.push_back(std::filesystem::path(data) / "fonts" / "DejaVuSans.ttf");
  if (std::string built = CLOTHLAB_FONT_FILE; !built.empty())
    candidates.emplace_back(built);
  for (const char* path : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",    // Debian, Ubuntu
                           "/usr/share/fonts/TTF/DejaVuSans.ttf",                // Arch
                           "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",  // Fedora
                           "/System/Library/Fonts/Supplemental/Arial Unicode.ttf",  // macOS
                           "/Library/Fonts/Arial Unicode.ttf"})
    candidates.emplace_back(path);
  return candidates;
}

// The letters the panel's texts use, in both languages: Latin-1 (é, è, à, ç, «», ², ·, ×),
// Latin Extended-A (œ), Greek (μ, ω, Δ, ε), the typographer's spaces, dashes, quotes and "…",
// arrows, the mathematical operators (√, ≤, ≈) and the angle brackets of ⟨n, u_w⟩.
constexpr ImWchar glyph_ranges[] = {
    0x0020, 0x00FF,  // Basic Latin and Latin-1
    0x0100, 0x017F,  // Latin Extended-A
    0x0370, 0x03FF,  // Greek
    0x2000, 0x206F,  // General Punctuation
    0x2070, 0x209F,  // superscripts and subscripts
    0x2190, 0x21FF,  // arrows
    0x2200, 0x22FF,  // mathematical operators
    0x27E8, 0x27E9,  // mathematical angle brackets
    0,
};

}  // namespace

bool add_panel_font(float size_pixels) {
  ImGuiIO& io = ImGui::GetIO();
  std::error_code ec;
  for (const std::filesystem::path& path : font_candidates()) {
    if (!std::filesystem::is_regular_file(path, ec))
      continue;
    ImFontConfig config;
    config.OversampleH = 2;  // crisper at a small size
    if (io.Fonts->AddFontFromFileTTF(path.string().c_str(), size_pixels, &config, glyph_ranges) !=
        nullptr)
      return true;
  }
  std::fprintf(stderr, "%s\n",
               tr("clothlab: warning: no DejaVu Sans font found (Debian's package "
                  "fonts-dejavu-core): the panel uses Dear ImGui's font, without accents"));
  ImFontConfig config;
  config.SizePixels = size_pixels;
  io.Fonts->AddFontDefault(&config);
  return false;
}

}  // namespace clothlab
