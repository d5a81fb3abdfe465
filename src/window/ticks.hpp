// The numbers on the axes of the panel's plots: round tick values and their labels, whose
// precision follows the spacing of the ticks, so that two ticks never read the same ("2.5",
// "2.5" on a total energy that varies by a thousandth). Pure logic, tested without a window.
#pragma once

#include <string>
#include <vector>

namespace clothlab {

// The round tick values in [low, high] (1, 2 or 5 times a power of ten apart), about `count`
// of them; at least two where the range allows.
std::vector<double> nice_ticks(double low, double high, int count);

// A number, short, to three significant digits: "0.05", "2e+03", "-1.5" (values that are not
// ticks, e.g. the stability map's K of each row).
std::string tick_label(double value);

// The labels of ticks `step` apart: as many digits as the step needs and no more ("61", "61.2",
// "61.4"; "2.4998", "2.5", "2.5002"), so that ticks that differ read differently.
std::string tick_label(double value, double step);

// The labels of evenly spaced ticks (nice_ticks'), each with the precision of their spacing.
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

}  // namespace clothlab
