#include "window/ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace clothlab {

std::vector<double> nice_ticks(double low, double high, int count) {
  std::vector<double> ticks;
  if (!(high > low) || !std::isfinite(low) || !std::isfinite(high) || count < 1)
    return ticks;
  const double raw = (high - low) / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= raw)
      break;
  }
  // Each tick is a whole multiple of the step, computed from its index (not by adding the step
  // again and again, whose rounding would pile up).
  const double first = std::ceil(low / step);
  for (double i = first; i * step <= high + 1e-9 * step; i += 1.0)
    ticks.push_back(std::abs(i) < 0.5 ? 0.0 : i * step);
  if (ticks.size() < 2 && count < 64)  // a lone tick gives no scale: a finer step
    return nice_ticks(low, high, 2 * count);
  return ticks;
}

std::string tick_label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string tick_label(double value, double step) {
  if (!(step > 0.0) || !std::isfinite(step) || !std::isfinite(value))
    return tick_label(value);
  if (std::abs(value) < 1e-9 * step)
    return "0";
  // The step's last digit, e.g. -1 for 0.2 or 0.5, 2 for 500 (a step of 2.5 needs one more).
  int last_digit = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  if (std::abs(step / std::pow(10.0, last_digit) - std::round(step / std::pow(10.0, last_digit))) >
      1e-6)
    --last_digit;
  // %g with the digits from the value's first to the step's last: 61.2 with a step of 0.2 needs
  // 3; %g drops the trailing zeros ("61" for 61.0) and switches to 2e+03 for large values.
  const int first_digit = static_cast<int>(std::floor(std::log10(std::abs(value)) + 1e-12));
  const int digits = std::clamp(first_digit - last_digit + 1, 1, 15);
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  const double step = ticks.size() >= 2 ? ticks[1] - ticks[0] : 0.0;
  std::vector<std::string> labels;
  labels.reserve(ticks.size());
  for (const double tick : ticks)
    labels.push_back(tick_label(tick, step));
  return labels;
}

}  // namespace clothlab
