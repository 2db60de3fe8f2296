// Every bad option of either program: one line on stderr naming the option and what is
// wrong, exit 1, and nothing started (a simulator that would serve prints its address).

#include "support/run_process.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

using subfeed::testing::run_process;

namespace {

struct BadOption {
  std::vector<std::string> argv;
  std::string option;  // named in the message
  std::string problem; // part of what the message says is wrong
};

void check_refused(const BadOption& bad) {
  CAPTURE(bad.argv);
  const auto result = run_process(bad.argv);
  CAPTURE(result.err);
  CHECK(result.exit_code == 1);
  CHECK(result.out.empty());
  CHECK(std::ranges::count(result.err, '\n') == 1);
  CHECK(result.err.ends_with("\n"));
  CHECK(result.err.find(bad.option) != std::string::npos);
  CHECK(result.err.find(bad.problem) != std::string::npos);
}

} // namespace

TEST_CASE("subfeed-sim refuses each bad option in one line, exit 1") {
  const std::string sim = SUBFEED_SIM_BIN;
  const std::vector<BadOption> cases = {
      {{sim, "grbl", "--tcp", "localhost:abc"}, "--tcp", "'localhost:abc'"},
      {{sim, "grbl", "--tcp", "localhost"}, "--tcp", "HOST:PORT"},
      {{sim, "grbl", "--tcp", ":5000"}, "--tcp", "HOST:PORT"},
      {{sim, "grbl", "--tcp", "localhost:70000"}, "--tcp", "0..65535"},
      {{sim, "grbl", "--tcp", "localhost:12x"}, "--tcp", "'localhost:12x'"},
      {{sim, "grbl", "--error-on-line", "-3"}, "--error-on-line", "'-3' is not a number above 0"},
      {{sim, "grbl", "--reset-on-line", "0"}, "--reset-on-line", "above 0"},
      {{sim, "grbl", "--alarm-after", "soon"}, "--alarm-after", "'soon' is not a number"},
      {{sim, "grbl", "--speed", "1,5"}, "--speed", "'1,5' is not a number"},
      {{sim, "grbl", "--ack-delay", "-5"}, "--ack-delay", "-5"},
      {{sim, "grbl", "--rx", "5"}, "--rx", "5"},
      {{sim, "grbl", "--axes", "7"}, "--axes", "7"},
      {{sim, "grbl", "--work-offset", "1,2"}, "--work-offset", ""},
      {{sim, "grbl", "--no-such-option"}, "--no-such-option", "not expected"},
      {{sim, "fanuc", "--framing", "9X9"}, "--framing", "'9X9'"},
      {{sim, "fanuc", "--low", "100", "--high", "50"}, "--low", "--high"},
      {{sim, "fanuc", "--drop-at", "-1"}, "--drop-at", "above 0"},
      {{sim, "fanuc", "--max-pause", "-1"}, "--max-pause", "-1"},
      {{sim, "plc"}, "plc", "unknown command"},
  };
  for (const auto& bad : cases) {
    check_refused(bad);
  }
}

TEST_CASE("subfeed refuses each bad option in one line, exit 1") {
  const std::string subfeed = SUBFEED_BIN;
  const std::string dome = std::string(SUBFEED_SOURCE_DIR) + "/examples/dome.obj";
  const std::vector<std::string> plan = {subfeed, "plan", dome, "--tool", "ball:6"};
  const auto with = [](std::vector<std::string> argv, std::initializer_list<std::string> more) {
    argv.insert(argv.end(), more);
    return argv;
  };
  const std::vector<BadOption> cases = {
      {with(plan, {"--scallop", "0.01", "--direction", "abc"}), "--direction", "'abc'"},
      {with(plan, {"--scallop", "0,01"}), "--scallop", "0,01"},
      {{subfeed, "plan", dome, "--tool", "ball:x", "--scallop", "0.01"}, "--tool", "'ball:x'"},
      {{subfeed, "plan", dome, "--tool", "ball:1,5", "--scallop", "0.01"}, "--tool", "'ball:1,5'"},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--baud", "fast"}, "--baud", "fast"},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--data-bits", "9"}, "--data-bits", "9"},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--status-hz", "-1"},
       "--status-hz",
       "-1"},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--protocol", "x"}, "--protocol", "x"},
      {{subfeed, "frobnicate"}, "frobnicate", "unknown command"},
  };
  for (const auto& bad : cases) {
    check_refused(bad);
  }
}
