// The checks between options, made once every value is read: the ranges that combine options
// (mu dt <= 1), the bounds of the run's own numbers (steps, image size, sweep), and the options
// that do not fit the others. Each throws usage_error naming the option (docs/cli.md).
#pragma once

#include <functional>
#include <string_view>

#include "app/option_values.hpp"
#include "app/options.hpp"

namespace clothlab {

// Whether the command line gave the option.
using given_option = std::function<bool(std::string_view option)>;

void check_other_ranges(options& o, const given_values& values);
void check_combinations(const options& o, const given_values& values, const given_option& given);

}  // namespace clothlab
