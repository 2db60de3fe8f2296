// The subfeed front as a user runs it: exit codes, one-line errors, help everywhere.

#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

using subfeed::testing::has_line;
using subfeed::testing::has_line_matching;
using subfeed::testing::literal;
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
  for (const char* line :
       {"  inspect                     Check a control cage and report its limit surface",
        "  plan                        Plan constant-scallop finishing passes on a cage",
        "  resume                      Continue a job from its journal after a fault",
        "  verify                      Measure the scallop and gouges a CL path leaves",
        "  config                      Validate machine configs and tool tables and show what they "
        "say",
        "  ports                       List this computer's serial ports",
        "  post                        Post-process CL data into G-code for one machine"}) {
    CHECK(has_line(help.out, line));
  }
}

TEST_CASE("every subcommand has --help") {
  for (const std::string cmd :
       {"inspect", "plan", "verify", "config", "send", "ports", "post", "check", "run", "resume"}) {
    INFO(cmd);
    const auto help = run_process({bin, cmd, "--help"});
    CHECK(help.exit_code == 0);
    CHECK(has_line_matching(help.out, "Usage: subfeed " + cmd + " \\[OPTIONS\\].*"));
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
  const auto cage = source_dir + "/examples/seat.obj";
  CHECK(r.out == "cage " + cage +
                     ": 63 vertices, 48 faces (48 quads), 0 extraordinary vertices, 28 boundary "
                     "edges, 0 creases, 0 corners, 0 holes, boundary edge only, creasing normal, "
                     "triangles catmark\n"
                     "setup: up z, 1 mm per model unit, zero at the model's zero (program zero "
                     "at model point 0.0000, 0.0000, 0.0000 mm)\n"
                     "limit surface: 48 patches, area 201.382 mm^2 (approximation level 4, 64 "
                     "samples per face edge)\n"
                     "  X    -8.8350 ..     8.8350 mm  (size 17.6700 mm)\n"
                     "  Y    -5.5100 ..     5.5100 mm  (size 11.0200 mm)\n"
                     "  Z     0.0000 ..     4.2300 mm  (size 4.2300 mm)\n"
                     "  steepest slope 72.6 deg from horizontal (near 8.467, -2.130, 0.623)\n");
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
  // An ISO 8601 UTC time, the level, and the line the user would have seen.
  CHECK(has_line_matching(
      first, R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ info )" +
                 literal(source_dir + "/configs/grbl-router-3axis.toml: 'GRBL 3-axis "
                                      "router', kinematics xyz, protocol grbl, dialect grbl")));
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
