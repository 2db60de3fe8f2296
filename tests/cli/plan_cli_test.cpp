// `subfeed plan` and `subfeed verify` as a user runs them.

#include "sim/pty.hpp"
#include "support/hand_made_cl.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <thread>

using namespace std::chrono_literals;
using subfeed::testing::BackgroundProcess;
using subfeed::testing::run_process;
using subfeed::testing::TempDir;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;

} // namespace

TEST_CASE("plan then verify the sample bowl", "[slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "bowl.cl").string();
  const auto svg = (dir.path() / "bowl.svg").string();
  const auto cage = source_dir + "/examples/bowl.obj";
  const auto plan = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.03",
                                 "--tolerance", "0.002", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  CHECK(plan.out.find("deformed CL surface") != std::string::npos);
  CHECK(plan.err.find("planning") == std::string::npos); // stderr is no terminal: no progress
  const auto verify = run_process({bin, "verify", cage, cl, "--tool", "ball:6", "--scallop", "0.03",
                                   "--spacing", "0.3", "--svg", svg});
  CHECK(verify.exit_code == 0);
  CHECK(verify.out.find("scallop max 0.03") != std::string::npos); // within 5 % of 0.03
  CHECK(std::filesystem::file_size(svg) > 1000);
  // What plan writes, post reads: a 5-axis path for the grblHAL trunnion.
  const auto post =
      run_process({bin, "post", cl, "--machine", source_dir + "/configs/grblhal-xyzac-trt.toml",
                   "-o", (dir.path() / "bowl.nc").string()});
  CHECK(post.exit_code == 0);
  // --direction auto: the summary names the direction cut and every candidate's price.
  const auto chosen = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.03",
                                   "--tolerance", "0.002", "--direction", "auto", "-o", cl});
  REQUIRE(chosen.exit_code == 0);
  CHECK(chosen.out.find("  feed direction ") != std::string::npos);
  CHECK(chosen.out.find(" deg, chosen by predicted cutting: 0 deg ") != std::string::npos);
  CHECK(chosen.out.find(" mm, 45 deg ") != std::string::npos);
  CHECK(chosen.out.find("  parallel passes kept by predicted cutting: rings ") !=
        std::string::npos);
}

TEST_CASE("plan --direction concentric cuts rings about the dome's top", "[slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "dome.cl").string();
  const auto cage = source_dir + "/examples/dome.obj";
  const auto plan = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.03",
                                 "--tolerance", "0.002", "--direction", "concentric", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  CHECK(plan.out.find("(concentric rings)") != std::string::npos);
  CHECK(plan.out.find("  concentric rings about (0.00, 0.00, ") != std::string::npos);
  const auto verify = run_process(
      {bin, "verify", cage, cl, "--tool", "ball:6", "--scallop", "0.03", "--spacing", "0.3"});
  CHECK(verify.exit_code == 0);
  CHECK(verify.out.find("scallop max 0.03") != std::string::npos); // within 5 % of 0.03
}

TEST_CASE("plan shows its progress on a terminal and erases it before the summary", "[pty]") {
  TempDir dir;
  const auto cl = (dir.path() / "bowl.cl").string();
  auto terminal = subfeed::sim::Pty::open().value(); // the user's terminal, as stderr
  BackgroundProcess planner({bin, "plan", source_dir + "/examples/bowl.obj", "--tool", "ball:6",
                             "--scallop", "0.03", "--tolerance", "0.002", "-o", cl},
                            "/dev/null", terminal.slave_path());
  std::atomic<bool> done{false};
  subfeed::testing::ProcessResult result;
  std::thread waiter([&] {
    result = planner.wait();
    done = true;
  });
  std::string shown;
  char buffer[4096];
  const auto take = [&](std::chrono::milliseconds wait) {
    if (const auto n = terminal.read(buffer, wait); n && *n > 0) {
      shown.append(buffer, *n);
    }
  };
  while (!done) {
    take(100ms);
  }
  waiter.join();
  for (int i = 0; i < 5; ++i) {
    take(20ms);
  }
  CHECK(result.exit_code == 0);
  CHECK(result.out.find("deformed CL surface") != std::string::npos);
  INFO(shown);
  CHECK(shown.find("\r\033[Kplanning 00:00  meshing the limit surface") != std::string::npos);
  CHECK(shown.find("  deformation solve 1 (at most 60)") != std::string::npos);
  CHECK(shown.find("%  plane 0 of ") != std::string::npos);
  CHECK(shown.find(" ETA ") != std::string::npos);
  const auto last = shown.rfind("planning ");
  REQUIRE(last != std::string::npos);
  CHECK(shown.find("\r\033[K", last) != std::string::npos); // erased after the last one
}

namespace {

// z = a (x^2 + y^2) on a 9 x 9 cage 2 mm apart: 1/(2a) mm in radius at the bottom.
std::string narrow_bowl_obj(double a) {
  std::string obj;
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 9; ++i) {
      const double x = 2.0 * (i - 4), y = 2.0 * (j - 4);
      obj += fmt::format("v {} {} {}\n", x, y, a * (x * x + y * y) - 2.0 * a * 4.0 / 3.0);
    }
  }
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) {
      const int v = 9 * j + i + 1;
      obj += fmt::format("f {} {} {} {}\n", v, v + 1, v + 10, v + 9);
    }
  }
  return obj;
}

} // namespace

TEST_CASE("plan warns of material left only where it is thicker than the scallop", "[slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "part.cl").string();
  // The sample seat and bowl: every place is reached or keeps less than H: one line, "none".
  for (const char* part : {"seat", "bowl"}) {
    CAPTURE(part);
    const auto plan = run_process({bin, "plan", source_dir + "/examples/" + part + ".obj", "--tool",
                                   "ball:6", "--scallop", "0.03", "-o", cl});
    REQUIRE(plan.exit_code == 0);
    CHECK(plan.out.find("material left thicker than H (0.03 mm): none") != std::string::npos);
    CHECK(plan.err.find("warning") == std::string::npos);
  }
  // Not a hollow, but lifted at the boundary corners: the path's own balls pass nearer than
  // H there, so that is a note, not a warning.
  const auto dome = run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool", "ball:6",
                                 "--scallop", "0.03", "-o", cl});
  REQUIRE(dome.exit_code == 0);
  CHECK(dome.out.find("CL points lifted clear of the part leave at most 0.0") != std::string::npos);
  CHECK(dome.err.find("warning") == std::string::npos);
  // z = r (x^2 + y^2) / 8 is 4 mm in radius at the bottom; a 5 mm ball rests on its walls
  // (5 - 4)^2 / 8 = 0.125 mm above it; the lifted points there keep one mesh tolerance more.
  const auto cage = dir.write("narrow.obj", narrow_bowl_obj(0.125)).string();
  const auto plan = run_process({bin, "plan", cage, "--tool", "ball:10", "--scallop", "0.1",
                                 "--tolerance", "0.005", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  CHECK(plan.err.find("is left in 1 place(s) the ball cannot follow") != std::string::npos);
  const auto at = plan.err.find("near (0.00, 0.00,");
  REQUIRE(at != std::string::npos);
  const auto up_to = plan.err.find("up to ", at);
  REQUIRE(up_to != std::string::npos);
  const double shown = std::stod(plan.err.substr(up_to + 6));
  CHECK(shown >= 0.125 - 0.002);
  CHECK(shown <= 0.125 + 0.005 + 0.01);
  CHECK(plan.err.find("a hollow narrower than the ball") != std::string::npos);
}

TEST_CASE("plan refuses a bad tool, scallop, direction, stay-down or cage in one line") {
  TempDir dir;
  const auto cage = source_dir + "/examples/bowl.obj";
  const auto tool = run_process({bin, "plan", cage, "--tool", "flat:6", "--scallop", "0.01"});
  CHECK(tool.exit_code == 1);
  CHECK(tool.err == "subfeed: error: --tool: 'flat:6': expected ball:D, a ball-end mill of "
                    "diameter D mm (0 < D <= 100)\n");
  const auto scallop = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "3"});
  CHECK(scallop.exit_code == 1);
  CHECK(scallop.err.find("--scallop: must be more than 0 and less than the ball radius") !=
        std::string::npos);
  const auto direction =
      run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.01", "--direction", "z"});
  CHECK(direction.exit_code == 1);
  CHECK(
      direction.err ==
      "subfeed: error: --direction: 'z': expected x, y, auto, concentric or an angle in degrees\n");
  const auto stay_down = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.01",
                                      "--stay-down", "-1", "-o", (dir.path() / "s.cl").string()});
  CHECK(stay_down.exit_code == 1);
  CHECK(stay_down.err.starts_with("subfeed: usage: --stay-down: Value -1 not in range"));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "s.cl"));
  const auto bad = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const auto cage_error = run_process({bin, "plan", bad.string(), "--tool", "ball:6", "--scallop",
                                       "0.01", "-o", (dir.path() / "x.cl").string()});
  CHECK(cage_error.exit_code == 2);
  CHECK(cage_error.err.starts_with("subfeed: error: " + bad.string() + ":4: "));
  CHECK_FALSE(std::filesystem::exists(dir.path() / "x.cl"));
}

TEST_CASE("verify refuses CL data without a cutting move") {
  TempDir dir;
  const auto cl = dir.write("rapid.cl", "UNITS/MM\nCUTTER/6,3\nRAPID\nGOTO/0,0,10\nFINI\n");
  const auto r = run_process(
      {bin, "verify", source_dir + "/examples/plane.obj", cl.string(), "--tool", "ball:6"});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + cl.string() + ": no cutting moves in the CL data\n");
}

TEST_CASE("verify writes a PNG, and refuses an unwritable one in one line without leaving a file") {
  TempDir dir;
  const auto cl = dir.write("line.cl", "UNITS/MM\nCUTTER/6,3\nMULTAX/ON\nFEDRAT/500\n"
                                       "GOTO/-5,0,0,0,0,1\nGOTO/5,0,0,0,0,1\nFINI\n");
  const auto cage = source_dir + "/examples/plane.obj";
  const auto png = dir.path() / "plane.png";
  const auto ok = run_process({bin, "verify", cage, cl.string(), "--tool", "ball:6", "--spacing",
                               "2", "--png", png.string()});
  CHECK(ok.exit_code == 0);
  std::ifstream in(png, std::ios::binary);
  std::string signature(8, '\0');
  in.read(signature.data(), 8);
  CHECK(signature == "\x89PNG\r\n\x1a\n");
  const auto missing = dir.path() / "no-such-dir" / "plane.png";
  const auto bad = run_process({bin, "verify", cage, cl.string(), "--tool", "ball:6", "--spacing",
                                "2", "--png", missing.string()});
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.starts_with("subfeed: error: "));
  CHECK(bad.err.find(missing.string()) != std::string::npos);
  CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(missing));
}

TEST_CASE("plan refused by the motion gate writes no CL file, names the line and exits 2",
          "[parts][slow]") {
  // A gate tolerance of 0.1 um is finer than the plan's own rounding on the dome: its first
  // cut that reaches deeper is refused where it stands.
  TempDir dir;
  const auto cl = (dir.path() / "dome.cl").string();
  const auto plan =
      run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool", "ball:6", "--scallop",
                   "0.05", "--refine", "2", "--gate-tolerance", "0.0001", "-o", cl});
  CHECK(plan.exit_code == 2);
  INFO(plan.err);
  CHECK(plan.err.rfind("subfeed: error: " + cl + ":", 0) == 0);
  CHECK(plan.err.find(": tool path refused: the cutting move from (") != std::string::npos);
  CHECK(plan.err.find("mm into the part (tolerance 0.0001 mm) at (") != std::string::npos);
  CHECK(plan.err.find("; nothing written\n") != std::string::npos);
  CHECK(std::count(plan.err.begin(), plan.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(cl));
  // At the default 1 um the same plan passes and says what was checked.
  const auto passed = run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool",
                                   "ball:6", "--scallop", "0.05", "--refine", "2", "-o", cl});
  REQUIRE(passed.exit_code == 0);
  CHECK(passed.out.find("checked against the part (its mesh within 0.25 um): no cut deeper than "
                        "1 um, no rapid touching it") != std::string::npos);
  CHECK(std::filesystem::exists(cl));
}

TEST_CASE("verify tells a rapid through the part from cutting gouges", "[unit]") {
  // Over the plane z = 0: one pass on it, then a rapid whose ball ends 1 mm below it.
  TempDir dir;
  const auto cl = dir.write("through.cl", subfeed::testing::rapid_through_plane_cl);
  const auto verify = run_process(
      {bin, "verify", source_dir + "/examples/plane.obj", cl.string(), "--tool", "ball:6"});
  CHECK(verify.exit_code == 0);
  CHECK(verify.out.find("\n  gouges 0 samples deeper than 0.1 um, deepest 0.000000 mm\n"
                        "  links (plunges and retracts): none reach into the part\n"
                        "  rapids: 3135 samples inside their sweep, deepest 1.000000 mm (near "
                        "-10.000, 5.000, 0.000)\n") != std::string::npos);
}
