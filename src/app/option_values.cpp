#include "app/option_values.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "core/i18n.hpp"

namespace clothlab {
namespace {

constexpr int max_list_values = 200;  // of a sweep's list

}  // namespace

std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

void require(bool ok, const std::string& option, double value, const std::string& what) {
  if (!ok)
    throw usage_error{option + " " + format_number(value) + colon() + what};
}

void require_finite(const std::string& option, double value) {
  require(std::isfinite(value), option, value, tr("must be a finite number"));
}

// low <= value <= high, named with the bounds: "--dt 1e-320: must be between 1e-09 and 1 s".
void require_within(const std::string& option, double value, const bounds& b) {
  require_finite(option, value);
  std::string what = format(tr("must be between %s and %s"), format_number(b.low).c_str(),
                            format_number(b.high).c_str());
  if (!b.unit.empty()) {
    what += ' ';
    what += b.unit;
  }
  require(value >= b.low && value <= b.high, option, value, what);
}

// One number, the same way for every option: the whole text must be a number (strtod's
// syntax). A value too large for a double is not a finite number; one too small to be a
// normal double (1e-320) is read as it is, and the option's range then decides.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())))
    return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size())
    return std::nullopt;
  if (errno == ERANGE && std::abs(x) == HUGE_VAL)
    return std::numeric_limits<double>::infinity();  // overflow: refused as not finite
  return x;
}

double number_or_usage_error(const std::string& option, const std::string& text,
                             const std::string& expected) {
  const std::optional<double> x = parse_number(text);
  if (!x)
    throw usage_error{option + " " + text + colon() + expected};
  return *x;
}

// "X,Y,Z" -> three finite numbers.
glm::dvec3 parse_vector(const std::string& option, const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::optional<double> x = parse_number(item);
    if (!x || !std::isfinite(*x)) {
      throw usage_error{option + " " + text + colon() + tr("expected three finite numbers X,Y,Z")};
    }
    values.push_back(*x);
  }
  if (values.size() != 3 || (!text.empty() && text.back() == ',')) {
    throw usage_error{option + " " + text + colon() + tr("expected three numbers X,Y,Z")};
  }
  return {values[0], values[1], values[2]};
}

// "A,B,C" (the values) or "FROM:TO:COUNT" (COUNT values spaced evenly on a log scale, both ends
// included), every one of them within `range` (checked before the values are computed, so that
// a range like 1e-300:1e300 cannot overflow on the way).
std::vector<double> parse_list(const std::string& option, const std::string& text,
                               const bounds& range) {
  auto number = [&](const std::string& item) {
    const std::optional<double> x = parse_number(item);
    if (!x || !std::isfinite(*x)) {
      throw usage_error{option + " " + text + colon() +
                        format(tr("'%s' is not a finite number"), item.c_str())};
    }
    return *x;
  };
  std::vector<std::string> items;
  const char separator = text.find(':') != std::string::npos ? ':' : ',';
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, separator);)
    items.push_back(item);
  if (items.empty() || text.back() == separator) {
    throw usage_error{option + " " + text + colon() + tr("expected A,B,C or FROM:TO:COUNT")};
  }
  std::vector<double> values;
  if (separator == ':') {
    if (items.size() != 3)
      throw usage_error{option + " " + text + colon() + tr("expected FROM:TO:COUNT")};
    const double from = number(items[0]);
    const double to = number(items[1]);
    const double count = number(items[2]);
    if (!(from > 0 && to > 0) || count != std::floor(count) || count < 2 ||
        count > max_list_values) {
      throw usage_error{option + " " + text + colon() +
                        format(tr("FROM and TO must be positive and COUNT a whole number from 2 "
                                  "to %d"),
                               max_list_values)};
    }
    require_within(option, from, range);
    require_within(option, to, range);
    // x_i = from (to / from)^(i / (count - 1)); through logarithms when to / from is not a
    // finite positive double (1e-320:1 would make it infinite, 1:1e-320 zero).
    const double ratio = to / from;
    const bool ratio_finite = std::isfinite(ratio) && ratio > 0;
    for (int i = 0; i < int(count); ++i) {
      const double fraction = i / (count - 1);
      values.push_back(ratio_finite
                           ? from * std::pow(ratio, fraction)
                           : std::exp(std::log(from) + fraction * (std::log(to) - std::log(from))));
    }
    values.front() = from;  // exactly, not within rounding of the bounds
    values.back() = to;
  } else {
    for (const std::string& item : items)
      values.push_back(number(item));
    for (double x : values)
      require_within(option, x, range);
    if (values.size() > max_list_values)
      throw usage_error{option + " " + text + colon() +
                        format(tr("at most %d values"), max_list_values)};
  }
  return values;
}

}  // namespace clothlab
