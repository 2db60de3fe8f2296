// `subfeed post` and `subfeed check` as a user runs them on the shipped examples.

#include "support/hand_made_cl.hpp"
#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

using subfeed::testing::has_line;
using subfeed::testing::has_line_matching;
using subfeed::testing::line_captures;
using subfeed::testing::literal;
using subfeed::testing::run_process;
using subfeed::testing::split_lines;
using subfeed::testing::TempDir;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;

} // namespace

TEST_CASE("post then check the 5-axis example for each shipped five-axis machine and dialect") {
  TempDir dir;
  for (const std::string machine :
       {"grblhal-xyzac-trt", "fanuc-xyzac-trt", "linuxcnc-xyzbc-trt", "grblhal-xyzac-head"}) {
    for (const std::string dialect : {"grbl", "fanuc", "linuxcnc"}) {
      INFO(machine << " " << dialect);
      const auto nc = (dir.path() / (machine + "-" + dialect + ".nc")).string();
      const auto config = source_dir + "/configs/" + machine + ".toml";
      const auto cl = source_dir + "/examples/dome-spiral.cl";
      const auto post =
          run_process({bin, "post", cl, "--machine", config, "--dialect", dialect, "-o", nc});
      REQUIRE(post.exit_code == 0);
      // Every pose of the CL file posted; the counts depend on the machine.
      CHECK(has_line_matching(post.out,
                              literal(nc + ": 803 poses -> ") +
                                  R"(\d+ lines \(\d+ blocks, \d+ from splitting to 0\.002 mm / )"
                                  R"(0\.05 deg\), \d+ repositionings, \d+ poses with C held near )"
                                  R"(the pole \(axis within \d+\.\d{4} deg\); trace in )" +
                                  literal(nc + ".map")));
      const auto check = run_process({bin, "check", nc, "--machine", config, "--cl", cl});
      CHECK(check.exit_code == 0);
      CHECK(has_line(check.out, "  limit violations 0, rotary jumps over 180 deg 0, blocks over "
                                "an axis max feed 0"));
      CHECK(check.out.ends_with("\n  check passed\n"));
    }
  }
}

TEST_CASE("check fails with exit 2 when the program leaves the CL path") {
  TempDir dir;
  const auto nc = (dir.path() / "bowl.nc").string();
  const auto config = source_dir + "/configs/grbl-router-3axis.toml";
  const auto cl = source_dir + "/examples/bowl-raster.cl";
  REQUIRE(run_process({bin, "post", cl, "--machine", config, "-o", nc}).exit_code == 0);
  std::string program = subfeed::testing::read_text(nc);
  const auto at = program.find("\nX-15.");
  REQUIRE(at != std::string::npos);
  program.replace(at, 6, "\nX-15.1");
  std::ofstream(nc) << program;
  const auto check = run_process({bin, "check", nc, "--machine", config, "--cl", cl});
  CHECK(check.exit_code == 2);
  CHECK(check.err == "subfeed: error: " + nc + ": check failed: see the report above\n");
}

TEST_CASE("post refuses bad input in one line, exit 2, and writes nothing") {
  TempDir dir;
  const auto cl = dir.write("bad.cl", "UNITS/MM\nCUTTER/6\nFEDRAT/100\nGOTO/1,2\nFINI\n");
  const auto nc = dir.path() / "bad.nc";
  const auto post =
      run_process({bin, "post", cl.string(), "--machine",
                   source_dir + "/configs/grbl-router-3axis.toml", "-o", nc.string()});
  CHECK(post.exit_code == 2);
  CHECK(post.err == "subfeed: error: " + cl.string() + ":4: GOTO needs x,y,z (MULTAX is off)\n");
  CHECK_FALSE(std::filesystem::exists(nc));
  const auto tcp = run_process({bin, "post", source_dir + "/examples/dome-spiral.cl", "--machine",
                                source_dir + "/configs/grblhal-xyzac-trt.toml", "--tcp", "angles",
                                "-o", nc.string()});
  CHECK(tcp.exit_code != 0);
  CHECK_FALSE(std::filesystem::exists(nc));
}

TEST_CASE("post --cage refuses a rapid through the part, naming its line, and writes nothing") {
  TempDir dir;
  const auto cl = dir.write("through.cl", subfeed::testing::rapid_through_plane_cl);
  const auto nc = dir.path() / "through.nc";
  const std::string router = source_dir + "/configs/grbl-router-3axis.toml";
  const auto post = run_process({bin, "post", cl.string(), "--machine", router, "--cage",
                                 source_dir + "/examples/plane.obj", "-o", nc.string()});
  CHECK(post.exit_code == 2);
  CHECK(post.err == "subfeed: error: " + cl.string() +
                        ":16: tool path refused: the rapid from (10.0000, 0.0000, 2.0000) to "
                        "(-10.0000, 5.0000, -1.0000) touches the part (the ball 1.0000 mm deep) "
                        "at (-10.0000, 5.0000, 0.0000)\n");
  CHECK_FALSE(std::filesystem::exists(nc));
  CHECK_FALSE(std::filesystem::exists(nc.string() + ".map"));
  // Without the rapid the same path passes, and the summary says what was checked.
  const auto good = dir.write("good.cl", subfeed::testing::rapid_through_plane_sound_part_cl);
  const auto ok = run_process({bin, "post", good.string(), "--machine", router, "--cage",
                               source_dir + "/examples/plane.obj", "-o", nc.string()});
  INFO(ok.err);
  CHECK(ok.exit_code == 0);
  CHECK(has_line(ok.out, "  motion gate: 5 moves (2 rapids) checked against the part (its limit "
                         "surface itself): no cut deeper than 1 um, no rapid touching it"));
  // The posted blocks too, as the machine moves: the post's own moves included.
  CHECK(has_line_matching(ok.out, R"(  posted program: [0-9]+ poses \([0-9]+ in rapids\) as the )"
                                  R"(machine moves its joints checked against the part: no cut )"
                                  R"(deeper than 3 um, no rapid touching it)"));
  CHECK(std::filesystem::exists(nc));
}

TEST_CASE("check refuses what it cannot replay, naming the line, and needs the trace map") {
  TempDir dir;
  const auto config = source_dir + "/configs/grbl-router-3axis.toml";
  const auto arc = dir.write("arc.nc", "G21 G90\nG0 X0 Y0 Z5\nG2 X10 Y0 I5 J0 F100\n");
  const auto r = run_process({bin, "check", arc.string(), "--machine", config});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + arc.string() +
                     ":3: G2 is not understood by check (arcs, cycles, inches and incremental "
                     "moves are not replayed)\n");
  const auto no_feed = dir.write("nofeed.nc", "G0 X0 Y0 Z5\nG1 X10\n");
  const auto f = run_process({bin, "check", no_feed.string(), "--machine", config});
  CHECK(f.exit_code == 2);
  CHECK(f.err == "subfeed: error: " + no_feed.string() + ":2: feed move without a feed rate (F)\n");
  const auto no_map = run_process({bin, "check", no_feed.string(), "--machine", config, "--cl",
                                   source_dir + "/examples/bowl-raster.cl"});
  CHECK(no_map.exit_code == 2);
  CHECK(no_map.err == "subfeed: error: " + no_feed.string() +
                          ".map: comparing with CL data needs the trace map subfeed post writes "
                          "beside the program\n");
}

TEST_CASE("check fails with exit 2 when a block under tool-centre-point control turns the axis "
          "off the CL path, the tip staying on it") {
  TempDir dir;
  const auto nc = (dir.path() / "dome.nc").string();
  const auto config = source_dir + "/configs/fanuc-xyzac-trt.toml";
  const auto cl = source_dir + "/examples/dome-spiral.cl";
  REQUIRE(
      run_process({bin, "post", cl, "--machine", config, "--tcp", "angles", "-o", nc}).exit_code ==
      0);
  const auto good = run_process({bin, "check", nc, "--machine", config, "--cl", cl});
  REQUIRE(good.exit_code == 0);
  // One cutting block's A half a degree off: under G43.4 the tip is where X Y Z say.
  std::string program = subfeed::testing::read_text(nc);
  const auto lines = split_lines(program);
  std::size_t at = std::string::npos;
  for (std::size_t i = lines.size() / 2; i < lines.size() && at == std::string::npos; ++i) {
    const auto a = lines[i].find(" A");
    if (lines[i].starts_with("G1") || (lines[i].starts_with("X") && a != std::string::npos)) {
      at = i;
    }
  }
  REQUIRE(at != std::string::npos);
  const auto a = lines[at].find(" A") + 2;
  const auto end = lines[at].find(' ', a);
  const double angle = std::stod(lines[at].substr(a, end - a));
  std::string bad = lines[at];
  bad.replace(a, end - a, fmt::format("{:.4f}", angle + 0.5));
  program.replace(program.find(lines[at]), lines[at].size(), bad);
  std::ofstream(nc) << program;
  const auto check = run_process({bin, "check", nc, "--machine", config, "--cl", cl});
  CHECK(check.exit_code == 2);
  const auto deviation = line_captures(
      check.out, R"(  against .*: [0-9]+ cutting blocks, tool tip deviation max ([0-9.]+) mm .*, )"
                 R"(tool axis deviation max ([0-9.]+) deg .*)");
  REQUIRE(deviation.size() == 3);
  CHECK(std::stod(deviation[1]) <= 0.002);
  CHECK(std::stod(deviation[2]) >= 0.4);
}
