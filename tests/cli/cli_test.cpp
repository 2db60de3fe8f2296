// The subfeed front as a user runs it: exit codes, one-line errors, help everywhere.

#include "support/run_process.hpp"
#include "support/temp_dir.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

using subfeed::testing::run_process;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;

long count_lines(const std::string& text) {
  return std::ranges::count(text, '\n');
}

} // namespace

TEST_CASE("the front answers --version and --help with exit 0") {
  const auto version = run_process({bin, "--version"});
  CHECK(version.exit_code == 0);
  CHECK(version.out.starts_with("subfeed "));
  const auto help = run_process({bin, "--help"});
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("inspect") != std::string::npos);
  CHECK(help.out.find("config") != std::string::npos);
}

TEST_CASE("every subcommand has --help") {
  for (const std::string cmd :
       {"inspect", "plan", "verify", "config", "send", "ports", "post", "check"}) {
    INFO(cmd);
    const auto help = run_process({bin, cmd, "--help"});
    CHECK(help.exit_code == 0);
    CHECK(help.out.find("Usage: subfeed " + cmd) != std::string::npos);
  }
}

TEST_CASE("usage errors exit 1 with one line") {
  for (const auto& args :
       std::vector<std::vector<std::string>>{{bin},
                                             {bin, "frobnicate"},
                                             {bin, "--bogus", "inspect", "x.obj"},
                                             {bin, "inspect"},
                                             {bin, "-v", "--quiet", "config", "x.toml"},
                                             {bin, "inspect", "x.obj", "--level", "2"}}) {
    const auto r = run_process(args);
    CHECK(r.exit_code == 1);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.starts_with("subfeed: usage: "));
  }
}

TEST_CASE("a malformed machine config exits 2 naming file and key in one line") {
  const subfeed::testing::TempDir dir;
  std::ifstream in(source_dir + "/configs/grblhal-xyzac-trt.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  const std::string anchor = "baud = 115200\n";
  const auto at = config.find(anchor);
  REQUIRE(at != std::string::npos);
  config.insert(at + anchor.size(), "stop_bits = 3\n");
  const long line = std::count(config.begin(), config.begin() + static_cast<long>(at), '\n') + 2;
  const auto bad = dir.write("bad.toml", config);
  const auto r = run_process({bin, "config", bad.string()});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + bad.string() + ":" + std::to_string(line) +
                     ": controller.serial.stop_bits: 3 is outside 1..2\n");
  CHECK(r.out.empty());
}

TEST_CASE("inspect reports the sample seat's extent") {
  const auto r =
      run_process({bin, "inspect", source_dir + "/examples/seat.obj", "--samples", "64"});
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.find("(size 17.6700 mm)") != std::string::npos);
  CHECK(r.out.find("(size 4.2300 mm)") != std::string::npos);
}

TEST_CASE("a bad cage exits 2 with file and line") {
  const subfeed::testing::TempDir dir;
  const auto cage = dir.write("c.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
  const auto r = run_process({bin, "inspect", cage.string()});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + cage.string() +
                     ":4: vertex index 7 is out of range (3 vertices defined so far)\n");
}

TEST_CASE("with --quiet nothing is printed and --log keeps everything, timestamped") {
  const subfeed::testing::TempDir dir;
  const auto log = dir.path() / "run.log";
  const auto r = run_process({bin, "--quiet", "--log", log.string(), "config",
                              source_dir + "/configs/grbl-router-3axis.toml"});
  CHECK(r.exit_code == 0);
  CHECK(r.out.empty());
  std::ifstream in(log);
  std::string first;
  std::getline(in, first);
  CHECK(first.find(" info ") != std::string::npos);
  CHECK(first.find("GRBL 3-axis router") != std::string::npos);
  CHECK(first[4] == '-'); // ISO date first
}

TEST_CASE("an unwritable --log is a bad-input error naming it") {
  const auto r = run_process({bin, "--log", "/nonexistent/dir/run.log", "config",
                              source_dir + "/configs/grbl-router-3axis.toml"});
  CHECK(r.exit_code == 2);
  CHECK(r.err ==
        "subfeed: error: /nonexistent/dir/run.log: --log: cannot open log file for appending\n");
}

TEST_CASE("subfeed-sim has --help and --version") {
  CHECK(run_process({SUBFEED_SIM_BIN, "--help"}).exit_code == 0);
  CHECK(run_process({SUBFEED_SIM_BIN, "--version"}).exit_code == 0);
  CHECK(run_process({SUBFEED_SIM_BIN, "nonsense"}).exit_code == 1);
}
