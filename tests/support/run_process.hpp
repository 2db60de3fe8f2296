#pragma once
// Runs a program to completion with its stdout and stderr captured, for testing the
// command-line fronts as a user runs them.

#include <string>
#include <vector>

namespace subfeed::testing {

struct ProcessResult {
  int exit_code = -1; // -1 when killed by a signal
  std::string out;
  std::string err;
};

[[nodiscard]] ProcessResult run_process(const std::vector<std::string>& argv);

} // namespace subfeed::testing
