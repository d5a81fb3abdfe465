// The parameter table (src/core/parameter_table.hpp) against docs/cli.md, and against itself:
// every parameter has its row in the document, written as the table writes it (range, default,
// unit), and every default and slider lies within the range that the command line accepts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/parameter_table.hpp"

namespace {

using namespace clothlab;

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream file(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);)
    lines.push_back(line);
  return lines;
}

constexpr const char* cli_doc = CLOTHLAB_SOURCE_DIR "/docs/cli.md";

// docs/cli.md has one row per parameter, the one the table writes. On a failure the message
// gives the row to write (CLOTHLAB_PRINT_PARAMETER_ROWS=1 prints them all).
TEST(parameter_table, EveryParameterHasItsRowInTheCommandLineDocument) {
  const std::vector<std::string> lines = lines_of(cli_doc);
  ASSERT_FALSE(lines.empty()) << cli_doc << " cannot be read";
  for (const parameter& p : parameter_table) {
    const std::string row = doc_row(p);
    if (std::getenv("CLOTHLAB_PRINT_PARAMETER_ROWS") != nullptr)
      std::printf("%s\n", row.c_str());
    const std::string start = "| `" + std::string(p.option) + " ";
    std::vector<std::string> rows;
    for (const std::string& line : lines) {
      if (line.rfind(start, 0) == 0)
        rows.push_back(line);
    }
    if (rows.size() != 1) {
      ADD_FAILURE() << cli_doc << " has " << rows.size() << " rows for " << p.option
                    << "; its row is\n"
                    << row;
      continue;
    }
    EXPECT_EQ(rows.front(), row) << cli_doc << "'s row for " << p.option
                                 << " differs from the parameter table (src/core/"
                                    "parameter_table.hpp); the table's row is\n"
                                 << row;
  }
}

// Every stage's default lies within the command line's range (a parameter that is off by
// default excepted), and every slider offers only values the command line accepts.
TEST(parameter_table, DefaultsAndSlidersLieWithinTheRange) {
  single_spring_parameters spring;
  coupled_springs_parameters coupled;
  cloth_parameters cloth;
  const stage_structs defaults{spring, coupled, cloth};
  for (const parameter& p : parameter_table) {
    int stages = 0;
    for (const stage_kind stage : {stage_kind::spring, stage_kind::coupled, stage_kind::cloth}) {
      const field_ref field = p.field(defaults, stage);
      if (!field)
        continue;
      ++stages;
      const double value = field.get();
      if (p.off.empty() || value != 0.0) {
        EXPECT_TRUE(value >= p.low && value <= p.high)
            << p.option << ": the " << stage_name(stage) << " stage's default " << value
            << " is outside " << range_text(p);
      }
      const slider_range slider = p.slider_for(stage);
      EXPECT_LT(slider.low, slider.high) << p.option;
      // A slider of a parameter that can be off starts at 0, the off position.
      EXPECT_TRUE((slider.low >= p.low || (!p.off.empty() && slider.low == 0.0)) &&
                  slider.high <= p.high)
          << p.option << ": the " << stage_name(stage) << " stage's slider " << slider.low << " to "
          << slider.high << " offers values outside " << range_text(p);
      if (slider.logarithmic) {
        EXPECT_GE(slider.low, 0.0) << p.option << ": a log slider over negative values";
      }
    }
    EXPECT_GE(stages, 1) << p.option << " sets no stage's field";
  }
}

// The rows as the document writes them: exponents short, units after the range, defaults by
// stage where they differ.
TEST(parameter_table, RowsAreWrittenAsTheDocumentWritesThem) {
  EXPECT_EQ(parameter_number(1e-9), "1e-9");
  EXPECT_EQ(parameter_number(1e9), "1e9");
  EXPECT_EQ(parameter_number(0.002), "0.002");
  EXPECT_EQ(range_text(parameter_named("--dt")), "1e-9 to 10 s");
  EXPECT_EQ(range_text(parameter_named("--mu")), "at least 0");
  EXPECT_EQ(default_text(parameter_named("--dt")), "spring and chain 0.01, cloth 0.002");
  EXPECT_EQ(default_text(parameter_named("--tear-strain")), "never");
  EXPECT_EQ(help_text(parameter_named("--N")), "Cloth grid size: N x N particles: 2 to 1024 [20]");
}

}  // namespace
