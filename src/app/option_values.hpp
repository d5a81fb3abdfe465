// Reading the command line's values: numbers, X,Y,Z vectors, the sweep's lists, and the checks
// that refuse a value with a message naming the option and the value (docs/cli.md, "Exit status").
#pragma once

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/parameter_table.hpp"

namespace clothlab {

// The texts CLI11 reads, before they are checked and converted. Real numbers are read as text
// and converted by parse_number, so that "1e-320", "inf" and "1e999" mean the same whatever the
// option (docs/limits.md); whole numbers by CLI11, in decimal (below).
struct given_values {
  std::string stage = "cloth", backend = "cpu", gl = "auto", integrator, start, pins, ground_z;
  std::string wind_dir, scaling, sweep_dt, sweep_k, sweep_n, sweep_time, drag, sphere;
  std::string lang;  // (chosen before the others are read: parse_command_line)
  std::vector<std::string> real_parameters = std::vector<std::string>(parameter_table.size());
  std::vector<int> whole_parameters = std::vector<int>(parameter_table.size());
};

// A usage error: the option and what is wrong with its value (exit status 2).
struct usage_error {
  std::string message;
};

// The range of a value, both ends included, and its unit (empty for none).
struct bounds {
  double low, high;
  std::string_view unit;
};
inline bounds bounds_of(const parameter& p) {
  return {p.low, p.high, p.unit};
}

std::string format_number(double x);  // %g: "1e-09", "0.002"

// Throws usage_error "OPTION VALUE: WHAT" unless ok.
void require(bool ok, const std::string& option, double value, const std::string& what);
void require_finite(const std::string& option, double value);
// low <= value <= high, named with the bounds: "--dt 1e-320: must be between 1e-09 and 10 s".
void require_within(const std::string& option, double value, const bounds& b);

// One number, the same way for every option: the whole text must be a number (strtod's
// syntax). A value too large for a double is not a finite number; one too small to be a
// normal double (1e-320) is read as it is, and the option's range then decides.
std::optional<double> parse_number(const std::string& text);
// The number, or usage_error "OPTION TEXT: EXPECTED".
double number_or_usage_error(const std::string& option, const std::string& text,
                             const std::string& expected);
// "X,Y,Z" -> three finite numbers.
glm::dvec3 parse_vector(const std::string& option, const std::string& text);
// "A,B,C" (the values) or "FROM:TO:COUNT" (COUNT values spaced evenly on a log scale, both ends
// included), every one of them within `range`.
std::vector<double> parse_list(const std::string& option, const std::string& text,
                               const bounds& range);

}  // namespace clothlab
