#include "window/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/i18n.hpp"

namespace clothlab {

void line_plot(const char* id, std::span<const plot_series> series, const plot_style& style) {
  ImGui::PushID(id);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const float text_height = ImGui::GetTextLineHeight();
  ImGui::Dummy({width, style.height});

  // The data's ranges.
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low;
  double y_low = x_low, y_high = -x_low;
  for (const plot_series& s : series) {
    for (std::size_t i = 0; i < s.y.size() && i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
        continue;
      x_low = std::min<double>(x_low, s.x[i]);
      x_high = std::max<double>(x_high, s.x[i]);
      y_low = std::min<double>(y_low, s.y[i]);
      y_high = std::max<double>(y_high, s.y[i]);
    }
  }
  if (style.y_from_zero) {
    y_low = std::min(y_low, 0.0);
    y_high = std::max(y_high, 0.0);
  }
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImU32 frame_colour = IM_COL32(110, 110, 120, 255);
  const ImU32 text_colour = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  if (!std::isfinite(x_low) || !std::isfinite(y_low)) {
    draw.AddText({origin.x + 4.0f, origin.y + 2.0f}, text_colour, tr("no data yet"));
    ImGui::PopID();
    return;
  }
  if (x_high <= x_low)
    x_high = x_low + 1.0;
  // A flat curve gets a small range around its value, so that its value can be read.
  if (y_high - y_low <= 1e-6 * std::max(std::abs(y_low), std::abs(y_high))) {
    const double margin = std::max(std::abs(y_low) * 0.01, 1e-9);
    y_low -= margin;
    y_high += margin;
  }
  const double y_margin = 0.05 * (y_high - y_low);  // the curve does not touch the frame
  y_low -= y_margin;
  y_high += y_margin;

  const int y_tick_count = std::max(3, static_cast<int>(style.height / (1.7f * text_height)));
  const std::vector<double> y_ticks = nice_ticks(y_low, y_high, y_tick_count);
  const std::vector<std::string> y_labels = tick_labels(y_ticks);  // as precise as the spacing
  float label_width = style.min_label_width;
  if (style.x_numbers)  // the x unit goes under the y numbers
    label_width = std::max(label_width, ImGui::CalcTextSize(style.x_unit).x);
  for (const std::string& label : y_labels)
    label_width = std::max(label_width, ImGui::CalcTextSize(label.c_str()).x);
  const ImVec2 low = {origin.x + label_width + 6.0f, origin.y + 1.0f};
  const ImVec2 high = {origin.x + width - 1.0f,
                       origin.y + style.height - (style.x_numbers ? text_height + 3.0f : 2.0f)};
  const auto to_screen = [&](double x, double y) {
    return ImVec2{low.x + static_cast<float>((x - x_low) / (x_high - x_low)) * (high.x - low.x),
                  high.y - static_cast<float>((y - y_low) / (y_high - y_low)) * (high.y - low.y)};
  };

  draw.AddRectFilled(low, high, IM_COL32(30, 34, 44, 255));
  for (std::size_t i = 0; i < y_ticks.size(); ++i) {
    const float y = to_screen(x_low, y_ticks[i]).y;
    draw.AddLine({low.x, y}, {high.x, y}, IM_COL32(60, 64, 76, 255));
    draw.AddLine({low.x - 3.0f, y}, {low.x, y}, frame_colour);
    const std::string& label = y_labels[i];
    draw.AddText({low.x - 5.0f - ImGui::CalcTextSize(label.c_str()).x, y - text_height / 2},
                 text_colour, label.c_str());
  }
  const int x_tick_count =
      std::max(1, static_cast<int>((high.x - low.x) / (5.5f * ImGui::GetFontSize())));
  const std::vector<double> x_ticks = nice_ticks(x_low, x_high, x_tick_count);
  const std::vector<std::string> x_labels = tick_labels(x_ticks);
  for (std::size_t i = 0; i < x_ticks.size(); ++i) {
    const float x = to_screen(x_ticks[i], y_low).x;
    draw.AddLine({x, low.y}, {x, high.y}, IM_COL32(60, 64, 76, 255));
    draw.AddLine({x, high.y}, {x, high.y + 3.0f}, frame_colour);
    if (style.x_numbers) {
      const std::string& label = x_labels[i];
      const float half = ImGui::CalcTextSize(label.c_str()).x / 2;
      draw.AddText({std::clamp(x - half, low.x, high.x - 2 * half), high.y + 2.0f}, text_colour,
                   label.c_str());
    }
  }
  if (style.x_numbers && *style.x_unit != '\0') {
    // The unit at the left, under the y numbers.
    draw.AddText({origin.x, high.y + 2.0f}, text_colour, style.x_unit);
  }
  draw.AddRect(low, high, frame_colour);

  draw.PushClipRect(low, high, true);
  if (!style.title.empty()) {
    const float title_width = ImGui::CalcTextSize(style.title.c_str()).x;
    draw.AddText({high.x - title_width - 4.0f, low.y + 1.0f}, ImGui::GetColorU32(ImGuiCol_Text),
                 style.title.c_str());
  }
  std::vector<ImVec2> points;
  for (const plot_series& s : series) {
    points.clear();
    for (std::size_t i = 0; i < s.y.size() && i < s.x.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        points.push_back(to_screen(s.x[i], s.y[i]));
    }
    if (points.size() >= 2)
      draw.AddPolyline(points.data(), static_cast<int>(points.size()), s.colour, 0, 1.5f);
  }
  draw.PopClipRect();

  // The values under the mouse: every series at the nearest x.
  if (ImGui::IsMouseHoveringRect(low, high)) {
    const double x =
        x_low + (ImGui::GetIO().MousePos.x - low.x) / (high.x - low.x) * (x_high - x_low);
    ImGui::BeginTooltip();
    ImGui::Text("%s %.4g", *style.x_unit != '\0' ? style.x_unit : "x", x);
    for (const plot_series& s : series) {
      if (s.x.empty())
        continue;
      const auto nearest = std::lower_bound(s.x.begin(), s.x.end(), static_cast<float>(x));
      const std::size_t i = std::min<std::size_t>(nearest - s.x.begin(), s.x.size() - 1);
      if (i < s.y.size()) {
        ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(s.colour), "%s %.5g %s", s.name, s.y[i],
                           style.y_unit);
      }
    }
    ImGui::EndTooltip();
  }
  ImGui::PopID();
}

}  // namespace clothlab
