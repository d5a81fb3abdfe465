// The command line of docs/cli.md, parsed with CLI11 over the parameter table
// (core/parameter_table.hpp) into the options (options.hpp). Shared by the headless program and
// the window.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "app/options.hpp"

namespace clothlab {

struct parse_result {
  std::optional<options> parsed;  // set when the program should go on
  int exit_code = 0;              // when not: 0 after --help/--version, 2 after bad usage
};

// Parses argv. --help and --version print to stdout; bad usage prints one line to stderr
// naming the option and what is wrong. Options that every stage shares (--dt, --mu, --mass,
// --gravity, --integrator) are set in all three parameter structs.
parse_result parse_command_line(int argc, const char* const* argv);

// The text with its control characters escaped (a newline as \n, others as \xHH), so that a
// message that quotes a value stays one line.
std::string one_line(std::string_view text);

}  // namespace clothlab
