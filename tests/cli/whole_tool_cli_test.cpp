// The whole tool from the command line: `plan` with a shank, stick-out and holder keeps
// them clear of the part and above the floor, records them in the CL data, and `verify`
// and `post --cage` hold the path to what is recorded.

#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>

using subfeed::testing::has_line;
using subfeed::testing::has_line_matching;
using subfeed::testing::line_captures;
using subfeed::testing::run_process;
using subfeed::testing::TempDir;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;

// verify's line for `body`: its clearance to the part (infinity when farther than searched)
// and its lowest point's height over the floor, mm.
struct BodyLine {
  double to_part = 0.0, over_floor = 0.0;
};
BodyLine body_line(const std::string& out, const std::string& body) {
  const auto near = line_captures(out, "    " + body +
                                           R"(: ([0-9.]+) mm from the part near \([-0-9., ]+\), )"
                                           R"(lowest (-?[0-9.]+) mm above the floor.*)");
  if (near.size() == 3) {
    return {std::stod(near[1]), std::stod(near[2])};
  }
  const auto far = line_captures(out, "    " + body +
                                          R"(: more than [0-9.]+ mm from the part, lowest )"
                                          R"((-?[0-9.]+) mm above the floor.*)");
  REQUIRE(far.size() == 2);
  return {1e9, std::stod(far[1])};
}

double verified_max(const std::string& out) {
  const auto got =
      line_captures(out, R"(  scallop max ([0-9.]+) mm \(near -?[0-9.]+, -?[0-9.]+, )"
                         R"(-?[0-9.]+\), mean [0-9.]+ mm, 99th percentile [0-9.]+ mm)");
  return got.size() == 2 ? std::stod(got[1]) : 1e9;
}

// Plans `part` with the tool, verifies it, and checks every body keeps 0.5 mm from the part
// and stays above the floor, and the scallop within 5 % of H where it is cut.
void plan_and_verify_clear(const std::string& part, const std::vector<std::string>& tool,
                           const std::vector<std::string>& bodies, double h) {
  TempDir dir;
  const auto cl = (dir.path() / "part.cl").string();
  std::vector<std::string> plan{
      bin, "plan", source_dir + "/examples/" + part, "--scallop", std::to_string(h), "-o", cl};
  plan.insert(plan.end(), tool.begin(), tool.end());
  const auto planned = run_process(plan);
  INFO(planned.err);
  REQUIRE(planned.exit_code == 0);
  CHECK(has_line_matching(planned.out, R"(  tool: ball .*; floor z -?[0-9.]+ mm, stock 0 mm )"
                                       R"(below it, clearance 0\.5 mm.*)"));
  const auto text = subfeed::testing::read_text(cl);
  CHECK(text.find("\nPPRINT TOOL flute=") != std::string::npos);
  CHECK(text.find("\nPPRINT FIXTURE floor=") != std::string::npos);
  const auto verified = run_process(
      {bin, "verify", source_dir + "/examples/" + part, cl, "--tool", tool[1], "--spacing", "0.1"});
  INFO(verified.out << verified.err);
  REQUIRE(verified.exit_code == 0);
  for (const auto& body : bodies) {
    const auto line = body_line(verified.out, body);
    INFO(body);
    CHECK(line.to_part >= 0.5);
    CHECK(line.over_floor >= 0.0);
  }
  const auto ball = line_captures(verified.out, R"(    ball: cuts the part, lowest (-?[0-9.]+) )"
                                                R"(mm above the floor.*)");
  REQUIRE(ball.size() == 2);
  CHECK(std::stod(ball[1]) >= -0.001);
  CHECK(verified_max(verified.out) <= 1.05 * h);
}

} // namespace

TEST_CASE("the dome with a 32 mm holder on a 40 mm stick-out: every body clear, none under the "
          "floor",
          "[parts][slow]") {
  plan_and_verify_clear(
      "dome.obj", {"--tool", "ball:6", "--shank", "6", "--stickout", "40", "--holder", "32:40"},
      {"flutes", "shank", "holder 1"}, 0.05);
}

TEST_CASE("the dome and the seat with a lead and a tilt: every body still clear, the lean eased "
          "where the holder would reach the floor, and said so",
          "[parts][slow]") {
  plan_and_verify_clear(
      "dome.obj",
      {"--tool", "ball:6", "--shank", "6", "--stickout", "40", "--holder", "32:40", "--lead", "20"},
      {"flutes", "shank", "holder 1"}, 0.05);
  plan_and_verify_clear("seat.obj",
                        {"--tool", "ball:2", "--shank", "2", "--stickout", "20", "--holder",
                         "20:30", "--lead", "-10", "--tilt", "10", "--direction", "y"},
                        {"flutes", "shank", "holder 1"}, 0.03);
  TempDir dir;
  const auto planned =
      run_process({bin, "plan", source_dir + "/examples/dome.obj", "--tool", "ball:6", "--shank",
                   "6", "--stickout", "40", "--holder", "32:40", "--lead", "20", "--scallop",
                   "0.05", "-o", (dir.path() / "d.cl").string()});
  REQUIRE(planned.exit_code == 0);
  const auto eased = line_captures(
      planned.out, R"(  tool axis along passes: turns [0-9.]+ deg between poses on average, at )"
                   R"(most ([0-9.]+) deg \(near .*\); lead 20 deg, tilt 0 deg kept in full at )"
                   R"(([0-9.]+) % of ([0-9]+) points, eased toward the unleaned axis at ([0-9]+) )"
                   R"(\(down to ([0-9]+) %\) where the full lean would collide, pass the tilt )"
                   R"(limit or cut off the ball)");
  REQUIRE(eased.size() == 6);
  CHECK(std::stod(eased[2]) > 50.0); // most of the dome takes the whole lean
  CHECK(std::stol(eased[4]) > 0);    // its foot does not, with this holder
  CHECK(std::stod(eased[1]) < 10.0); // and the axis eases, no jump
}

TEST_CASE("the seat with a 20 mm holder on a 20 mm stick-out: every body clear, none under the "
          "floor",
          "[parts][slow]") {
  plan_and_verify_clear(
      "seat.obj", {"--tool", "ball:2", "--shank", "2", "--stickout", "20", "--holder", "20:30"},
      {"flutes", "shank", "holder 1"}, 0.03);
}

TEST_CASE("a ball alone is planned with the default flutes, shank and stick-out, and says so") {
  TempDir dir;
  const auto cl = (dir.path() / "plane.cl").string();
  const auto planned = run_process({bin, "plan", source_dir + "/examples/plane.obj", "--tool",
                                    "ball:6", "--scallop", "0.05", "-o", cl});
  REQUIRE(planned.exit_code == 0);
  CHECK(has_line_matching(planned.out,
                          R"(  tool: ball 6, flutes 18, shank 6, stick-out 24, no holder )"
                          R"(\(defaults: flutes 3D, shank D, stick-out 4D; give --flute, --shank, )"
                          R"(--stickout, --holder for the real tool\); floor z -?[0-9.]+ mm.*)"));
  CHECK(subfeed::testing::read_text(cl).find(
            "\nPPRINT TOOL flute=18 shank=6 stickout=24 holder=none\n") != std::string::npos);
}

TEST_CASE("a bad tool or fixture is one line naming the option, and nothing is written") {
  TempDir dir;
  const auto cl = (dir.path() / "x.cl").string();
  const auto plan = [&](const std::vector<std::string>& more) {
    std::vector<std::string> argv{bin,      "plan",   source_dir + "/examples/plane.obj",
                                  "--tool", "ball:6", "--scallop",
                                  "0.05",   "-o",     cl};
    argv.insert(argv.end(), more.begin(), more.end());
    return run_process(argv);
  };
  const auto holder = plan({"--holder", "32"});
  CHECK(holder.exit_code == 1);
  CHECK(holder.err == "subfeed: error: --holder: '32': expected D:L or D1:D2:L (diameters and "
                      "length in mm, each above 0 and at most 10000)\n");
  const auto stickout = plan({"--flute", "30", "--stickout", "20"});
  CHECK(stickout.exit_code == 1);
  CHECK(stickout.err == "subfeed: error: --stickout: the stick-out (20 mm) must be at least the "
                        "flute length (30 mm)\n");
  const auto lead = plan({"--lead", "50"});
  CHECK(lead.exit_code == 1);
  CHECK(lead.err == "subfeed: usage: --lead: Value 50 not in range -45.000000 to 45.000000 (see "
                    "subfeed --help)\n");
  const auto fixed = plan({"--tilt", "5", "--axis", "fixed"});
  CHECK(fixed.exit_code == 1);
  CHECK(fixed.err ==
        "subfeed: error: --tilt: a vertical tool (--axis fixed) cannot lead or tilt\n");
  const auto router =
      run_process({bin, "run", source_dir + "/examples/plane.obj", "--machine",
                   source_dir + "/configs/grbl-router-3axis.toml", "--tool", "ball:6", "--scallop",
                   "0.05", "--lead", "10", "--sim", "-o", (dir.path() / "router").string()});
  CHECK(router.exit_code == 1);
  CHECK(router.err == "subfeed: error: " + source_dir +
                          "/configs/grbl-router-3axis.toml: --lead: a three-axis machine holds "
                          "the tool vertical: it cannot lead or tilt\n");
  CHECK_FALSE(std::filesystem::exists(dir.path() / "router.nc"));
  const auto floor = plan({"--floor", "low"});
  CHECK(floor.exit_code == 1);
  CHECK(floor.err == "subfeed: error: --floor: 'low': expected a height in mm, or none (no floor "
                     "is checked)\n");
  CHECK_FALSE(std::filesystem::exists(cl));
}

TEST_CASE("a path whose recorded holder would hit the floor is refused by post --cage and verify",
          "[parts][slow]") {
  TempDir dir;
  const auto cl = (dir.path() / "seat.cl").string();
  const auto seat = source_dir + "/examples/seat.obj";
  REQUIRE(run_process({bin, "plan", seat, "--tool", "ball:2", "--scallop", "0.05", "--stickout",
                       "20", "--holder", "20:30", "-o", cl})
              .exit_code == 0);
  // The same path said to be held by a wide holder 6 mm above the tip.
  auto text = subfeed::testing::read_text(cl);
  const auto at = text.find("PPRINT TOOL ");
  REQUIRE(at != std::string::npos);
  text.replace(at, text.find('\n', at) - at, "PPRINT TOOL flute=6 shank=2 stickout=6 holder=40:30");
  const auto bad = (dir.path() / "bad.cl").string();
  std::ofstream(bad, std::ios::binary) << text;
  const auto nc = (dir.path() / "bad.nc").string();
  const auto posted =
      run_process({bin, "post", bad, "--machine", source_dir + "/configs/grblhal-xyzac-trt.toml",
                   "--cage", seat, "-o", nc});
  CHECK(posted.exit_code == 2);
  CHECK(has_line_matching(posted.err,
                          R"(subfeed: error: .*bad\.cl:\d+: tool path refused: .* takes the )"
                          R"(holder 1 [0-9.]+ mm below the floor at .*)"));
  CHECK_FALSE(std::filesystem::exists(nc));
  const auto verified = run_process({bin, "verify", seat, bad, "--tool", "ball:2"});
  CHECK(verified.exit_code == 2);
  CHECK(has_line_matching(
      verified.err, R"(subfeed: error: .*bad\.cl:\d+: the tool collides: \d+ measured poses )"
                    R"(break the fixture's rules, .*holder 1 goes below its floor limit .*)"));
}

TEST_CASE(
    "a tool by name (--tool NAME) comes from the tool table, the flags beside it win, and the CL "
    "data records the sizes, not the name") {
  TempDir dir;
  const auto table = dir.path() / "tools.toml";
  {
    std::ofstream out(table);
    out << "[long6]\ncutter = \"ball\"\ndiameter = 6\nflute = 20\nshank = 8\nstickout = 50\n"
           "holder = [[30, 40, 25], [60, 10]]\n";
  }
  const auto plan = [&](const std::string& cl, const std::vector<std::string>& more) {
    std::vector<std::string> argv{bin,         "plan", source_dir + "/examples/plane.obj",
                                  "--scallop", "0.05", "--floor",
                                  "none",      "-o",   (dir.path() / cl).string()};
    argv.insert(argv.end(), more.begin(), more.end());
    return run_process(argv);
  };
  const auto named = plan("named.cl", {"--tool", "long6", "--tools", table.string()});
  REQUIRE(named.exit_code == 0);
  CHECK(has_line(named.out, "tool long6 (" + table.string() +
                                ":1): --tool ball:6 --flute 20 --shank 8 --stickout 50 --holder "
                                "30:40:25 --holder 60:10"));
  const auto text = subfeed::testing::read_text(dir.path() / "named.cl");
  CHECK(text.find("\nCUTTER/6.,3.\n") != std::string::npos);
  CHECK(text.find("\nPPRINT TOOL flute=20 shank=8 stickout=50 holder=30:40:25,60:10\n") !=
        std::string::npos);
  // The same tool spelt out on the command line plans the same path.
  const auto spelt =
      plan("spelt.cl", {"--tool", "ball:6", "--flute", "20", "--shank", "8", "--stickout", "50",
                        "--holder", "30:40:25", "--holder", "60:10"});
  REQUIRE(spelt.exit_code == 0);
  CHECK(subfeed::testing::read_text(dir.path() / "spelt.cl") == text);
  const auto overridden = plan("over.cl", {"--tool", "long6", "--tools", table.string(),
                                           "--stickout", "30", "--holder", "25:20"});
  REQUIRE(overridden.exit_code == 0);
  CHECK(subfeed::testing::read_text(dir.path() / "over.cl")
            .find("\nPPRINT TOOL flute=20 shank=8 stickout=30 holder=25:20\n") !=
        std::string::npos);
  // configs/tools.toml is the default, from where the user stands (the project's top here).
  const auto shipped = run_process(
      {"/bin/sh", "-c",
       "cd '" + source_dir + "' && exec '" + bin +
           "' plan examples/plane.obj --tool ball6-er32 --scallop 0.05 --floor none -o '" +
           (dir.path() / "shipped.cl").string() + "'"});
  REQUIRE(shipped.exit_code == 0);
  CHECK(subfeed::testing::read_text(dir.path() / "shipped.cl")
            .find("\nPPRINT TOOL flute=18 shank=6 stickout=40 holder=32:40\n") !=
        std::string::npos);
}

TEST_CASE("a tool name the table lacks, a missing table and a bad table are one line each, and "
          "nothing is written") {
  TempDir dir;
  const auto cl = (dir.path() / "x.cl").string();
  const auto table =
      dir.write("tools.toml", "[a]\ncutter = \"ball\"\ndiameter = 6\n"
                              "[b]\ncutter = \"ball\"\ndiameter = 4\nholder = [[1]]\n");
  const auto plan = [&](const std::string& tool, const std::string& tools) {
    return run_process({bin, "plan", source_dir + "/examples/plane.obj", "--tool", tool, "--tools",
                        tools, "--scallop", "0.05", "-o", cl});
  };
  const auto missing = plan("c", table.string());
  CHECK(missing.exit_code == 2);
  CHECK(missing.err == "subfeed: error: " + table.string() +
                           ":7: b.holder: expected stages [D, L] or [D1, D2, L], bottom first, "
                           "each size above 0 and at most 10000 mm\n");
  const auto good = dir.write("good.toml", "[a]\ncutter = \"ball\"\ndiameter = 6\n"
                                           "[b]\ncutter = \"ball\"\ndiameter = 4\n");
  const auto unknown = plan("c", good.string());
  CHECK(unknown.exit_code == 1);
  CHECK(unknown.err == "subfeed: error: --tool: 'c' is neither ball:D nor a tool in " +
                           good.string() + " (it has: a, b)\n");
  const auto none = plan("a", (dir.path() / "none.toml").string());
  CHECK(none.exit_code == 1);
  CHECK(none.err == "subfeed: error: --tool: 'a' is not ball:D, and there is no tool table " +
                        (dir.path() / "none.toml").string() +
                        " to look it up in (give --tools FILE)\n");
  CHECK_FALSE(std::filesystem::exists(cl));
  const auto config = run_process({bin, "config", good.string()});
  CHECK(config.exit_code == 0);
  CHECK(has_line(config.out, good.string() + ": tool table, 2 tools"));
  CHECK(has_line(config.out, "  b (line 4): ball 4, flutes 3D, shank D, stick-out 4D, no holder"));
}

namespace {

// Over examples/plane.obj (z = 0), ball 6 mm, one pass along X on the plane with the tool
// axis `axis` (unit, in the XZ plane): the ball's centre 3 mm up, the tip 3 mm below it.
std::string pass_along_x(double ax, double az) {
  std::string cl = "PARTNO LEAN\nUNITS/MM\nCUTTER/6,3\nMULTAX/ON\n";
  const auto pose = [&](double x, double z_above) {
    return fmt::format("GOTO/{:.6f},0,{:.6f},{:.9f},0,{:.9f}\n", x - 3 * ax, 3 + z_above - 3 * az,
                       ax, az);
  };
  cl += "RAPID\n" + pose(-8, 20) + "RAPID\n" + pose(-8, 2) + "FEDRAT/300\nPLUNGE\n" + pose(-8, 0);
  cl += "FEDRAT/1000\n" + pose(8, 0) + "RETRACT\n" + pose(8, 20) + "FINI\n";
  return cl;
}

} // namespace

TEST_CASE("check with a cage: every body measured against the part and the floor, a holder "
          "tilted into the part is exit 2, the pass upright passes") {
  TempDir dir;
  const auto plane = source_dir + "/examples/plane.obj";
  const auto machine = source_dir + "/configs/grblhal-xyzac-trt.toml";
  const std::vector<std::string> tool{"--tool",     "ball:6", "--flute",  "9",
                                      "--stickout", "12",     "--holder", "40:20"};
  const auto check = [&](const std::string& name, double ax, double az) {
    const auto cl = dir.write(name + ".cl", pass_along_x(ax, az)).string();
    const auto nc = (dir.path() / (name + ".nc")).string();
    REQUIRE(run_process({bin, "post", cl, "--machine", machine, "-o", nc}).exit_code == 0);
    std::vector<std::string> argv{bin, "check", nc, "--machine", machine, "--cage", plane};
    argv.insert(argv.end(), tool.begin(), tool.end());
    return run_process(argv);
  };
  const auto upright = check("upright", 0.0, 1.0);
  INFO(upright.out << upright.err);
  CHECK(upright.exit_code == 0);
  CHECK(has_line_matching(upright.out, R"(  whole tool: ball 6, flutes 9, shank 6, stick-out 12, )"
                                       R"(holder 40:20; floor z 0\.000 mm, stock 0 mm below it, )"
                                       R"(clearance 0\.5 mm; [0-9]+ moves swept)"));
  const auto holder = body_line(upright.out, "holder 1");
  CHECK(holder.to_part > 5.5); // its face 12 mm over the plane, past what is searched
  CHECK(holder.over_floor == Approx(12.0).margin(0.01));
  CHECK(has_line(upright.out, "  check passed"));
  // Leaning 45 degrees, the holder's rim (20 mm from the axis, 12 mm up it) dips 4.8 mm
  // under the plane: z = 0.879 + 12 cos 45 - 20 sin 45.
  const auto leaning = check("leaning", std::sqrt(0.5), std::sqrt(0.5));
  INFO(leaning.out << leaning.err);
  CHECK(leaning.exit_code == 2);
  const auto under = body_line(leaning.out, "holder 1");
  CHECK(under.over_floor == Approx(0.879 + 12 * std::sqrt(0.5) - 20 * std::sqrt(0.5)).margin(0.01));
  CHECK(has_line_matching(leaning.err,
                          "subfeed: error: " + (dir.path() / "leaning.nc").string() +
                              R"(:[0-9]+: the tool collides: [0-9]+ measured poses break the )"
                              R"(fixture's rules, the first in the move to line [0-9]+: the )"
                              R"(holder 1 .*)"));
  // Without a tool there is nothing to measure: the flags or the CL data's records.
  const auto bare = run_process(
      {bin, "check", (dir.path() / "upright.nc").string(), "--machine", machine, "--cage", plane});
  CHECK(bare.exit_code == 1);
  CHECK(bare.err == "subfeed: error: --cage: the whole tool is needed: give --tool (with "
                    "--shank, --stickout, --holder), or --cl with CL data that records it "
                    "(PPRINT TOOL and FIXTURE)\n");
}
