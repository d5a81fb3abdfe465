#include "window/widgets.hpp"

#include <algorithm>
#include <unordered_map>
#include <vector>

namespace clothlab {

const char* ui_label(const char* english) {
  static std::unordered_map<std::string, std::string> labels;
  static unsigned generation = language_generation();
  if (generation != language_generation()) {
    labels.clear();
    generation = language_generation();
  }
  std::string& label = labels[english];
  if (label.empty())
    label = std::string(tr(english)) + "###" + english;
  return label.c_str();
}

float ui_scale() {
  return ImGui::GetFontSize() / 13.0f;
}

void fixed_lines(const std::string& text, int lines, text_style style, const ImVec4& colour,
                 float width) {
  if (width <= 0.0f)
    width = std::max(ImGui::GetContentRegionAvail().x, 1.0f);
  const auto fits = [&](const std::string& line) {
    return ImGui::CalcTextSize(line.c_str()).x <= width;
  };
  std::vector<std::string> shown;
  std::string line;
  bool cut = false;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos)
      end = text.size();
    const std::string word = text.substr(start, end - start);
    start = end + 1;
    const std::string longer = line.empty() ? word : line + " " + word;
    if (line.empty() || fits(longer)) {
      line = longer;
      continue;
    }
    shown.push_back(line);
    line = word;
    if (static_cast<int>(shown.size()) == lines) {
      cut = true;
      break;
    }
  }
  if (!cut && !line.empty())
    shown.push_back(line);
  if (static_cast<int>(shown.size()) > lines) {
    shown.resize(static_cast<std::size_t>(lines));
    cut = true;
  }
  if (cut && !shown.empty()) {
    std::string& last = shown.back();
    while (!last.empty() && !fits(last + " ...")) {
      const std::size_t space = last.rfind(' ');
      last.erase(space == std::string::npos ? 0 : space);
    }
    last += last.empty() ? "..." : " ...";
  }
  shown.resize(static_cast<std::size_t>(lines));  // empty lines keep the height
  ImGui::BeginGroup();
  for (const std::string& l : shown) {
    switch (style) {
      case text_style::plain:
        ImGui::TextUnformatted(l.c_str());
        break;
      case text_style::disabled:
        ImGui::TextDisabled("%s", l.c_str());
        break;
      case text_style::coloured:
        ImGui::TextColored(colour, "%s", l.c_str());
        break;
    }
  }
  ImGui::EndGroup();
  if (cut && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 35.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

bool slider(const char* label, double& value, double min, double max, const char* format,
            bool logarithmic) {
  const ImGuiSliderFlags flags =
      ImGuiSliderFlags_AlwaysClamp | (logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
  return ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &min, &max, format, flags);
}

bool slider(const char* label, int& value, int min, int max) {
  return ImGui::SliderInt(label, &value, min, max, "%d", ImGuiSliderFlags_AlwaysClamp);
}

bool section(const char* title) {
  return ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen);
}

}  // namespace clothlab
