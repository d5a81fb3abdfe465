// The numbers on the panel's plot axes (src/window/ticks.hpp): the precision follows the spacing
// of the ticks, so that no two ticks of an axis read the same.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "window/ticks.hpp"

namespace clothlab {
namespace {

// Every label of the axis is different from the others, and reads as its tick's value.
void expect_distinct_labels(double low, double high, int count) {
  const std::vector<double> ticks = nice_ticks(low, high, count);
  ASSERT_GE(ticks.size(), 2u) << "[" << low << ", " << high << "]";
  const std::vector<std::string> labels = tick_labels(ticks);
  ASSERT_EQ(labels.size(), ticks.size());
  const std::set<std::string> different(labels.begin(), labels.end());
  std::string all;
  for (const std::string& label : labels)
    all += label + " ";
  EXPECT_EQ(different.size(), labels.size()) << "[" << low << ", " << high << "]: " << all;
  const double step = ticks[1] - ticks[0];
  for (std::size_t i = 0; i < ticks.size(); ++i)
    EXPECT_NEAR(std::stod(labels[i]), ticks[i], 0.01 * step) << labels[i];
}

TEST(TickLabels, TheTotalEnergyOfTheOneDimensionalSpringReadsDifferentlyAtEveryTick) {
  // Stage 1 with the 1D start after about 45 s: the total energy varies by a few thousandths
  // around 2.5 J (it showed "2.5" twice).
  expect_distinct_labels(2.4991, 2.5012, 4);
  expect_distinct_labels(2.49995, 2.50004, 3);
}

TEST(TickLabels, TheTimeAxisOfADivergedRunReadsDifferentlyAtEveryTick) {
  // K = 50000 diverges at once: t spans a fraction of a second past 61 s (it showed "61" twice).
  expect_distinct_labels(60.9, 61.7, 6);
  expect_distinct_labels(61.0, 61.05, 6);
  expect_distinct_labels(1234.5, 1234.75, 5);
}

TEST(TickLabels, EveryRangeGivesDistinctLabels) {
  for (const double centre : {-3e5, -61.0, -2.5, 0.0, 1e-4, 0.3, 2.5, 61.0, 997.0, 4e6}) {
    for (const double width : {1e-5, 3e-4, 0.02, 0.7, 5.0, 130.0, 4e4}) {
      for (const int count : {2, 3, 5, 8})
        expect_distinct_labels(centre - width / 3, centre + 2 * width / 3, count);
    }
  }
}

TEST(TickLabels, RoundTicksStayShort) {
  EXPECT_EQ(tick_labels({0.0, 0.05, 0.1}), (std::vector<std::string>{"0", "0.05", "0.1"}));
  EXPECT_EQ(tick_labels({60.8, 61.0, 61.2}), (std::vector<std::string>{"60.8", "61", "61.2"}));
  EXPECT_EQ(tick_labels({-2.0, -1.0, 0.0, 1.0}), (std::vector<std::string>{"-2", "-1", "0", "1"}));
  EXPECT_EQ(tick_labels({2000.0, 4000.0}), (std::vector<std::string>{"2e+03", "4e+03"}));
  EXPECT_EQ(tick_label(20.0 * 1.7782794), "35.6");  // not a tick: three digits
}

}  // namespace
}  // namespace clothlab
