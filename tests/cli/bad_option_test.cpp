// Every bad option of either program: one line on stderr naming the option and what is
// wrong, exit 1, and nothing started (a simulator that would serve prints its address).

#include "support/run_process.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

using subfeed::testing::run_process;

namespace {

struct BadOption {
  std::vector<std::string> argv;
  std::string message; // the whole line on stderr after "PROGRAM: usage: "
};

void check_refused(const BadOption& bad) {
  CAPTURE(bad.argv);
  const auto result = run_process(bad.argv);
  CAPTURE(result.err);
  CHECK(result.exit_code == 1);
  CHECK(result.out.empty());
  CHECK(std::ranges::count(result.err, '\n') == 1);
  const std::string program = std::filesystem::path(bad.argv.front()).filename().string();
  CHECK(result.err == program + ": usage: " + bad.message + "\n");
}

// Values that parse but that the command refuses: exit 1 too, as an error of that option.
void check_refused_value(const std::vector<std::string>& argv, const std::string& message) {
  CAPTURE(argv);
  const auto result = run_process(argv);
  CHECK(result.exit_code == 1);
  CHECK(result.out.empty());
  CHECK(result.err == "subfeed: error: " + message + "\n");
}

} // namespace

TEST_CASE("subfeed-sim refuses each bad option in one line, exit 1") {
  const std::string sim = SUBFEED_SIM_BIN;
  const std::string help = " (see subfeed-sim --help)";
  const std::string tcp = "--tcp: expected HOST:PORT with a port 0..65535, got ";
  const std::vector<BadOption> cases = {
      {{sim, "grbl", "--tcp", "localhost:abc"}, tcp + "'localhost:abc'"},
      {{sim, "grbl", "--tcp", "localhost"}, tcp + "'localhost'"},
      {{sim, "grbl", "--tcp", ":5000"}, tcp + "':5000'"},
      {{sim, "grbl", "--tcp", "localhost:70000"}, tcp + "'localhost:70000'"},
      {{sim, "grbl", "--tcp", "localhost:12x"}, tcp + "'localhost:12x'"},
      {{sim, "grbl", "--error-on-line", "-3"},
       "--error-on-line: '-3' is not a number above 0" + help},
      {{sim, "grbl", "--reset-on-line", "0"},
       "--reset-on-line: '0' is not a number above 0" + help},
      {{sim, "grbl", "--alarm-after", "soon"},
       "--alarm-after: 'soon' is not a number above 0" + help},
      {{sim, "grbl", "--speed", "1,5"}, "--speed: '1,5' is not a number above 0" + help},
      {{sim, "grbl", "--ack-delay", "-5"}, "--ack-delay: Value -5 not in range 0 to 600000" + help},
      {{sim, "grbl", "--rx", "5"}, "--rx: Value 5 not in range 16 to 65536" + help},
      {{sim, "grbl", "--axes", "7"}, "--axes: Value 7 not in range 3 to 6" + help},
      {{sim, "grbl", "--work-offset", "1,2"},
       "--work-offset: At least 3 required but received 2" + help},
      {{sim, "grbl", "--no-such-option"},
       "The following argument was not expected: --no-such-option" + help},
      {{sim, "fanuc", "--framing", "9X9"}, "--framing: expected e.g. 7E2 or 8N1, got '9X9'"},
      {{sim, "fanuc", "--low", "100", "--high", "50"}, "need --low < --high <= --buffer"},
      {{sim, "fanuc", "--drop-at", "-1"}, "--drop-at: '-1' is not a number above 0" + help},
      {{sim, "fanuc", "--max-pause", "-1"},
       "--max-pause: Value -1 not in range 0 to 600000" + help},
      {{sim, "plc"}, "unknown command 'plc'" + help},
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
  const std::string help = " (see subfeed --help)";
  const std::vector<BadOption> cases = {
      {with(plan, {"--scallop", "0,01"}), "Could not convert: --scallop = 0,01" + help},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--baud", "fast"},
       "Could not convert: --baud = fast" + help},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--data-bits", "9"},
       "--data-bits: 9 not in {7,8}" + help},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--status-hz", "-1"},
       "--status-hz: Value -1 not in range 0.500000 to 20.000000" + help},
      {{subfeed, "send", "job.nc", "--port", "/dev/null", "--protocol", "x"},
       "--protocol: x not in {grbl,fanuc}" + help},
      {{subfeed, "frobnicate"}, "unknown command 'frobnicate'" + help},
  };
  for (const auto& bad : cases) {
    check_refused(bad);
  }
  const std::string ball = "': expected ball:D, a ball-end mill of diameter D mm (0 < D <= 100)";
  check_refused_value(with(plan, {"--scallop", "0.01", "--direction", "abc"}),
                      "--direction: 'abc': expected x, y, auto, concentric or an angle in degrees");
  check_refused_value({subfeed, "plan", dome, "--tool", "ball:x", "--scallop", "0.01"},
                      "--tool: 'ball:x" + ball);
  check_refused_value({subfeed, "plan", dome, "--tool", "ball:1,5", "--scallop", "0.01"},
                      "--tool: 'ball:1,5" + ball);
}
