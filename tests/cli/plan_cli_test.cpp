// `subfeed plan` and `subfeed verify` as a user runs them.

#include "sim/pty.hpp"
#include "support/hand_made_cl.hpp"
#include "support/output_lines.hpp"
#include "support/png_reader.hpp"
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

// The plan summary's first line for `cl`, with the method named.
std::string summary_line(const std::string& cl, const std::string& method) {
  return literal(cl) + R"(: \d+ passes, \d+ points, cutting [0-9.]+ mm, links [0-9.]+ mm \()" +
         literal(method) + R"(\))";
}

// The worst scallop verify measured, in mm (0 when the line is missing).
double verified_max(const std::string& out) {
  const auto got =
      line_captures(out, R"(  scallop max ([0-9.]+) mm \(near -?[0-9.]+, -?[0-9.]+, )"
                         R"(-?[0-9.]+\), mean [0-9.]+ mm, 99th percentile [0-9.]+ mm)");
  return got.size() == 2 ? std::stod(got[1]) : 0.0;
}

} // namespace

TEST_CASE("plan then verify the sample bowl", "[parts][slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "bowl.cl").string();
  const auto svg = (dir.path() / "bowl.svg").string();
  const auto cage = source_dir + "/examples/bowl.obj";
  const auto plan = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.03",
                                 "--tolerance", "0.002", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  CHECK(has_line_matching(plan.out, summary_line(cl, "deformed CL surface")));
  CHECK(plan.err.empty()); // stderr is no terminal: no progress, and nothing to warn of
  const auto verify = run_process({bin, "verify", cage, cl, "--tool", "ball:6", "--scallop", "0.03",
                                   "--spacing", "0.3", "--svg", svg});
  CHECK(verify.exit_code == 0);
  CHECK(verified_max(verify.out) > 0.0);
  CHECK(verified_max(verify.out) <= 1.05 * 0.03);
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
  CHECK(has_line_matching(chosen.out,
                          R"(  feed direction [0-9.]+ deg, chosen by predicted cutting: 0 deg \d+ )"
                          R"(mm, 45 deg \d+ mm, 90 deg \d+ mm, 135 deg \d+ mm, [0-9.]+ deg \d+ )"
                          R"(mm, [0-9.]+ deg \d+ mm(; solved in full: .*)?)"));
  CHECK(has_line_matching(chosen.out, R"(  parallel passes kept by predicted cutting: rings \d+ )"
                                      R"(mm against \d+ mm of parallel passes)"));
}

TEST_CASE("plan --direction concentric cuts rings about the dome's top", "[parts][slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "dome.cl").string();
  const auto cage = source_dir + "/examples/dome.obj";
  const auto plan = run_process({bin, "plan", cage, "--tool", "ball:6", "--scallop", "0.03",
                                 "--tolerance", "0.002", "--direction", "concentric", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  CHECK(has_line_matching(plan.out, summary_line(cl, "concentric rings")));
  CHECK(has_line_matching(plan.out,
                          R"(  concentric rings about \(0\.00, 0\.00, [0-9.]+\), \d )"
                          R"(marches of the front; ring spacing up to [0-9.]+ of the )"
                          R"(need(; passes inserted there down to 1/\d+ of a plane step)?)"));
  const auto verify = run_process(
      {bin, "verify", cage, cl, "--tool", "ball:6", "--scallop", "0.03", "--spacing", "0.3"});
  CHECK(verify.exit_code == 0);
  CHECK(verified_max(verify.out) > 0.0);
  CHECK(verified_max(verify.out) <= 1.05 * 0.03);
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
  CHECK(has_line_matching(result.out, summary_line(cl, "deformed CL surface")));
  INFO(shown);
  // Each frame erases the line and writes the stage; the last erases it for the summary.
  const std::string erase = "\r\033[K";
  REQUIRE(shown.starts_with(erase));
  CHECK(shown.ends_with(erase));
  std::vector<std::string> frames;
  for (std::size_t at = 0; at < shown.size();) {
    const auto next = shown.find(erase, at + erase.size());
    frames.push_back(shown.substr(at + erase.size(), next - at - erase.size()));
    at = next == std::string::npos ? shown.size() : next;
  }
  CHECK(frames.front() == "planning 00:00  meshing the limit surface");
  const auto any_frame = [&](const std::string& pattern) {
    return std::ranges::any_of(frames, [&](const std::string& f) {
      return has_line_matching(f, R"(planning \d\d:\d\d  )" + pattern);
    });
  };
  // Every stage of the planner shows as it starts.
  for (const auto* stage : {"meshing for the motion gate", "finding what the tool reaches",
                            "deformation solves", "clearing the ball"}) {
    CHECK(any_frame(literal(stage)));
  }
  CHECK(any_frame(literal("deformation solve 1 of at most 60  ETA --:--")));
  // A stage that tells its share shows it, with an ETA once there is a rate to tell one.
  CHECK(any_frame(R"(finding what the tool reaches \[[#.]+\] +\d+\.\d%  ETA (\d\d:\d\d|--:--))"));
  CHECK(any_frame(R"(\[[#.]+\] +\d+\.\d%  plane \d+ of \d+  ETA (\d\d:\d\d|--:--))"));
}

TEST_CASE("plan --verbose says where the time went, stage by stage") {
  TempDir dir;
  const auto cl = (dir.path() / "dome.cl").string();
  const auto r = run_process({bin, "--verbose", "plan", source_dir + "/examples/dome.obj", "--tool",
                              "ball:6", "--scallop", "0.05", "--tolerance", "0.002", "-o", cl});
  CHECK(r.exit_code == 0);
  const std::string s = R"(([0-9]+\.[0-9]{2}) s)";
  const auto times = line_captures(
      r.out, "  time: meshing the limit surface " + s + ", meshing for the motion gate " + s +
                 ", finding what the tool reaches " + s + ", deformation solves " + s +
                 R"( \(\d+ solves\), clearing the ball )" + s + ", slicing and linking " + s +
                 " \\(motion gate checks " + s + ", routing links " + s + ", handing poses on " +
                 s + "\\); " + s + " in all");
  REQUIRE(times.size() == 11); // the whole line, then each figure
  const auto figure = [&](std::size_t i) { return std::stod(times[i + 1]); };
  double stages = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    stages += figure(i);
  }
  // The parts add up (to the rounding of each figure).
  CHECK(std::abs(stages - figure(9)) <= 0.035);
  // The gate, the links' routing and the sink are within slicing.
  CHECK(figure(6) + figure(7) + figure(8) <= figure(5) + 0.015);
  CHECK(figure(9) > 0.0);
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

TEST_CASE("plan warns of material left only where it is thicker than the scallop",
          "[parts][slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "part.cl").string();
  // The sample seat and bowl: every place is reached or keeps less than H: one line, "none".
  for (const char* part : {"seat", "bowl"}) {
    CAPTURE(part);
    // No floor: the band round the foot a 6 mm ball reaches only below it is another warning.
    const auto plan = run_process({bin, "plan", source_dir + "/examples/" + part + ".obj", "--tool",
                                   "ball:6", "--scallop", "0.03", "--floor", "none", "-o", cl});
    REQUIRE(plan.exit_code == 0);
    CHECK(has_line_matching(plan.out,
                            literal("  material left thicker than H (0.03 mm): none") + "(; .*)?"));
    CHECK(plan.err.empty());
  }
  // Not a hollow, but lifted at the boundary corners: the path's own balls pass nearer than
  // H there, so that is a note, not a warning.
  const auto dome = run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool", "ball:6",
                                 "--scallop", "0.03", "--floor", "none", "-o", cl});
  REQUIRE(dome.exit_code == 0);
  CHECK(has_line_matching(dome.out, R"(  material left thicker than H \(0\.03 mm\): none(; \d+ )"
                                    R"(surface vertices in hollows narrower than the ball keep at )"
                                    R"(most 0\.0[0-2]\d+ mm)?; \d+ CL points lifted clear of the )"
                                    R"(part leave at most 0\.0[0-2]\d+ mm)"));
  CHECK(dome.err.empty());
  // z = r (x^2 + y^2) / 8 is 4 mm in radius at the bottom; a 5 mm ball rests on its walls
  // (5 - 4)^2 / 8 = 0.125 mm above it; the lifted points there keep one mesh tolerance more.
  // (Its flutes, as wide as the ball, graze the walls the ball touches near its equator: they
  // may here, with no clearance asked.)
  const auto cage = dir.write("narrow.obj", narrow_bowl_obj(0.125)).string();
  const auto plan =
      run_process({bin, "plan", cage, "--tool", "ball:10", "--scallop", "0.1", "--tolerance",
                   "0.005", "--floor", "none", "--clearance-min", "0", "-o", cl});
  REQUIRE(plan.exit_code == 0);
  const auto lines = split_lines(plan.err);
  INFO(plan.err);
  REQUIRE(lines.size() == 2);
  const auto all =
      line_captures(lines[0], R"(subfeed: warning:   material thicker than H \(0\.1 )"
                              R"(mm\) is left in 1 place\(s\) the ball cannot follow, )"
                              R"(up to ([0-9.]+) mm: finish them with a smaller ball)");
  const auto one =
      line_captures(lines[1], R"(subfeed: warning:     near \(0\.00, 0\.00, [0-9.]+\) )"
                              R"(mm, over [0-9.]+ x [0-9.]+ x [0-9.]+ mm: up to )"
                              R"(([0-9.]+) mm, a hollow narrower than the ball \(\d+ )"
                              R"(surface vertices, \d+ CL points lifted clear\))");
  REQUIRE(all.size() == 2);
  REQUIRE(one.size() == 2);
  CHECK(all[1] == one[1]);
  const double shown = std::stod(one[1]);
  CHECK(shown >= 0.125 - 0.002);
  CHECK(shown <= 0.125 + 0.005 + 0.01);
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
  CHECK(scallop.err ==
        "subfeed: error: --scallop: must be more than 0 and less than the ball radius\n");
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
  CHECK(bad.err == "subfeed: error: " + missing.string() +
                       ": cannot create output file: No such file or directory\n");
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
  const std::string point = R"(\(-?[0-9.]+, -?[0-9.]+, -?[0-9.]+\))";
  REQUIRE(split_lines(plan.err).size() == 1);
  CHECK(has_line_matching(plan.err, "subfeed: error: " + literal(cl) +
                                        R"(:\d+: tool path refused: the cutting move from )" +
                                        point + " to " + point +
                                        R"( cuts [0-9.]+ mm into the )"
                                        R"(part \(tolerance 0\.0001 mm\) at )" +
                                        point + "; nothing written"));
  CHECK_FALSE(std::filesystem::exists(cl));
  // At the default 1 um the same plan passes and says what was checked.
  const auto passed = run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool",
                                   "ball:6", "--scallop", "0.05", "--refine", "2", "-o", cl});
  REQUIRE(passed.exit_code == 0);
  CHECK(has_line_matching(passed.out, R"(  motion gate: \d+ moves \(\d+ rapids\) checked against )"
                                      R"(the part \(its limit surface itself\): no cut deeper )"
                                      R"(than 1 um, no rapid touching it; least clearance: ball )"
                                      R"(-?[0-9.]+ mm above the floor; flutes .*)"));
  CHECK(std::filesystem::exists(cl));
}

TEST_CASE("verify tells a rapid through the part from cutting gouges, and fails on it", "[unit]") {
  // Over the plane z = 0: one pass on it, then a rapid whose ball ends 1 mm below it.
  TempDir dir;
  const auto cl = dir.write("through.cl", subfeed::testing::rapid_through_plane_cl);
  const auto verify = run_process(
      {bin, "verify", source_dir + "/examples/plane.obj", cl.string(), "--tool", "ball:6"});
  CHECK(verify.exit_code == 2);
  CHECK(has_line(verify.err, "subfeed: error: " + cl.string() +
                                 ": a rapid reaches 1.000000 mm into the part near (-10.000, "
                                 "5.000, 0.000): on a machine that is a crash"));
  const auto sound = dir.write("sound.cl", subfeed::testing::rapid_through_plane_sound_part_cl);
  CHECK(run_process(
            {bin, "verify", source_dir + "/examples/plane.obj", sound.string(), "--tool", "ball:6"})
            .exit_code == 0);
  const auto lines = split_lines(verify.out);
  const auto gouges = std::ranges::find(lines, "  gouges 0 samples deeper than 0.1 um, deepest "
                                               "0.000000 mm");
  REQUIRE(gouges != lines.end());
  REQUIRE(lines.end() - gouges >= 3);
  CHECK(gouges[1] == "  links (plunges and retracts): none reach into the part");
  CHECK(gouges[2] == "  rapids: 3135 samples inside their sweep, deepest 1.000000 mm (near "
                     "-10.000, 5.000, 0.000)");
}

TEST_CASE("plan leaves a closed part's underside uncut and says how much, and verify measures it "
          "apart") {
  TempDir dir;
  const auto cage = (dir.path() / "block.obj").string();
  {
    std::ofstream obj(cage);
    // A box 20 x 20 x 16 mm standing on z = 0: its limit surface is closed.
    obj << "v -10 -10 0\nv 10 -10 0\nv 10 10 0\nv -10 10 0\n"
           "v -10 -10 16\nv 10 -10 16\nv 10 10 16\nv -10 10 16\n"
           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }
  const auto cl = (dir.path() / "block.cl").string();
  const auto planned = run_process({bin, "plan", cage, "--tool", "ball:4", "--scallop", "0.05",
                                    "--tolerance", "0.002", "--max-tilt", "60", "-o", cl});
  REQUIRE(planned.exit_code == 0);
  const std::string mm2 = R"(([0-9]+\.[0-9]) mm\^2)";
  const auto left = line_captures(planned.err, "subfeed: warning:   left uncut, out of the tool's "
                                               "reach: " +
                                                   mm2 +
                                                   R"( in 1 region\(s\) \(normals more than 60 )"
                                                   R"(deg from \+Z, hidden under the part, no )"
                                                   R"(clear tool axis, or below the floor\))");
  REQUIRE(left.size() == 2);
  CHECK(has_line_matching(planned.err,
                          R"(subfeed: warning:     near \(0\.00, 0\.00, [0-9.]+\) mm, )"
                          R"(over [0-9.]+ x [0-9.]+ x [0-9.]+ mm: [0-9.]+ mm\^2, )"
                          R"(normals up to 1[0-9.]+ deg from \+Z)"));
  const auto verified = run_process(
      {bin, "verify", cage, cl, "--tool", "ball:4", "--max-tilt", "60", "--spacing", "0.2"});
  REQUIRE(verified.exit_code == 0);
  const auto beyond = line_captures(verified.out, "  out of reach: " + mm2 +
                                                      R"( whose normals lean more than 60 deg )"
                                                      R"(from \+Z \(\d+ samples\), not measured )"
                                                      "for scallop");
  REQUIRE(beyond.size() == 2);
  // The planner leaves whole mesh cells round the edge: a little more than verify's samples.
  CHECK(std::stod(left[1]) >= std::stod(beyond[1]));
  CHECK(std::stod(left[1]) <= 1.05 * std::stod(beyond[1]));
  CHECK(verified_max(verified.out) <= 0.05 * 1.05);
  // Measured for a tool that could tilt to 90, the band the plan left between 60 and 90
  // degrees is surface no ball came to: dark grey in the picture, round the cut top.
  const auto png = (dir.path() / "block.png").string();
  const auto pictured = run_process({bin, "verify", cage, cl, "--tool", "ball:4", "--max-tilt",
                                     "90", "--spacing", "0.2", "--png", png});
  REQUIRE(pictured.exit_code == 0);
  const auto image = subfeed::testing::read_png(png);
  long grey = 0, scallop = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const auto at = static_cast<std::size_t>((y * image.width + x) * 3);
      const int r = image.rgb[at], g = image.rgb[at + 1], b = image.rgb[at + 2];
      grey += r == 96 && g == 96 && b == 96 ? 1 : 0;
      scallop += g <= 80 && r + b >= 250 && r + b <= 260 ? 1 : 0;
    }
  }
  const long swatch = 16L * 14L; // the legend's own
  CHECK(grey > 20 * swatch);
  CHECK(scallop > grey);
  // The tilt is checked as an option.
  const auto bad = run_process({bin, "plan", cage, "--tool", "ball:4", "--scallop", "0.05",
                                "--max-tilt", "200", "-o", cl + ".2"});
  CHECK(bad.exit_code == 1);
  CHECK(bad.err == "subfeed: usage: --max-tilt: Value 200 not in range 0.000000 to 180.000000 "
                   "(see subfeed --help)\n");
  CHECK_FALSE(std::filesystem::exists(cl + ".2"));
}

TEST_CASE("plan of a sheet that faces the table cuts nothing and says to turn it over") {
  TempDir dir;
  const auto cage = (dir.path() / "sheet.obj").string();
  {
    std::ofstream obj(cage);
    // A 3 x 3 face sheet at z = 0 wound clockwise seen from +Z: its surface faces -Z.
    for (int j = 0; j <= 3; ++j) {
      for (int i = 0; i <= 3; ++i) {
        obj << "v " << 10 * i << ' ' << 10 * j << " 0\n";
      }
    }
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        const int a = 1 + 4 * j + i;
        obj << "f " << a << ' ' << a + 4 << ' ' << a + 5 << ' ' << a + 1 << '\n';
      }
    }
  }
  const auto cl = (dir.path() / "sheet.cl").string();
  const auto down = run_process(
      {bin, "plan", cage, "--tool", "ball:3", "--scallop", "0.05", "--tolerance", "0.002", "-o", cl});
  REQUIRE(down.exit_code == 0);
  CHECK(has_line(down.err, "subfeed: warning:   nothing to cut: no surface faces the tool within "
                           "reach; an open sheet whose faces wind the other way faces down: plan "
                           "it with the opposite --up (-y for y)"));
  // Turned over, it is cut, and no such warning is given.
  const auto up = run_process({bin, "plan", cage, "--up", "-z", "--tool", "ball:3", "--scallop",
                               "0.05", "--tolerance", "0.002", "-o", cl});
  REQUIRE(up.exit_code == 0);
  CHECK(up.err.find("nothing to cut") == std::string::npos);
  CHECK(std::filesystem::file_size(cl) > 1000);
}
