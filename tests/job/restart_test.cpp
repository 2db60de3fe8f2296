// Where a resume restarts and how it gets there, on small programs with known answers.

#include "job/restart_approach.hpp"
#include "job/restart_point.hpp"
#include "post/kinematics.hpp"
#include "post/machine_config.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>

using namespace subfeed;
using namespace subfeed::job;
using subfeed::testing::TempDir;

namespace {

const std::string source = SUBFEED_SOURCE_DIR;

// Lines 1..6: modes, a rapid, three cuts along X, a mode line.
const char* const program = "G21 G90 G94\n"
                            "G0 X0 Y0 Z5\n"
                            "G1 Z0 F300\n"
                            "G1 X10\n"
                            "G1 X20 Y10\n"
                            "M9\n";

std::optional<RestartPoint> at(const std::string& file, std::vector<double> position) {
  auto window = read_window(file, 1, 6, 0);
  REQUIRE(window);
  return find_machine(*window, position, 3);
}

} // namespace

TEST_CASE("the machine is found at the end of a move, inside one, or nowhere") {
  TempDir dir;
  const auto file = dir.write("p.nc", program).string();
  SECTION("at the end of line 4: continue after it") {
    const auto p = at(file, {10.0, 0.0, 0.0});
    REQUIRE(p);
    CHECK(p->after == 4);
    CHECK_FALSE(p->mid_block);
  }
  SECTION("inside line 5, to the report's rounding: line 5 again from its start") {
    const auto p = at(file, {15.0004, 5.0, 0.0});
    REQUIRE(p);
    CHECK(p->after == 4);
    CHECK(p->mid_block);
  }
  SECTION("at the end of the last move: nothing moved after it") {
    const auto p = at(file, {20.0, 10.0, 0.0});
    REQUIRE(p);
    CHECK(p->after == 5);
  }
  SECTION("off every move by more than the rounding") {
    CHECK_FALSE(at(file, {15.0, 5.002, 0.0}));
    CHECK_FALSE(at(file, {15.0, 5.0, 0.01}));
  }
}

TEST_CASE("line ends carry every axis word in force and the TCP mode") {
  TempDir dir;
  const auto file =
      dir.write("t.nc", "G0 X1 Y2 Z3 A4 C5\nG43.4 H1\nX7 (X99 in a comment)\nG49\n").string();
  auto window = read_window(file, 1, 4, 0);
  REQUIRE(window);
  CHECK(window->line_end.at(1).words == Joints{1, 2, 3, 4, 0, 5});
  CHECK_FALSE(window->line_end.at(1).tcp);
  CHECK(window->line_end.at(3).words[0] == 7.0);
  CHECK(window->line_end.at(3).tcp);
  CHECK_FALSE(window->line_end.at(4).tcp);
  CHECK(window->moves.size() == 2);
}

TEST_CASE("a sequence number is found at its last use up to the last line sent") {
  TempDir dir;
  const auto file = dir.write("n.nc", "%\nO1\nN1 G21\nN2 G0 X1\nN1 G1 X2\nN2 X3\n%\n").string();
  CHECK(find_sequence_number(file, 1, 6).value() == 5);
  CHECK(find_sequence_number(file, 2, 5).value() == 4);
  const auto missing = find_sequence_number(file, 3, 6);
  REQUIRE_FALSE(missing);
  CHECK(missing.error().where.key == "--block");
}

TEST_CASE("a control that ran dry may be given the first block not sent, and no later one") {
  TempDir dir;
  const auto file =
      dir.write("n.nc", "%\nO1\nN1 G21\nN2 G0 X1\n(note)\nN3 G1 X2\nN4 X3\n%\n").string();
  CHECK(find_sequence_number(file, 3, 4).value() == 6); // past a comment line
  CHECK(find_sequence_number(file, 3, 5).value() == 6);
  CHECK(find_sequence_number(file, 2, 5).value() == 4); // sent: found among the sent
  CHECK_FALSE(find_sequence_number(file, 4, 4));        // two blocks on: would skip N3
  CHECK_FALSE(find_sequence_number(file, 4, 5));
}

TEST_CASE("under TCP the restart point's joints put the tool tip where the words say") {
  const auto machine = post::load_machine_config(source + "/configs/fanuc-xyzac-trt.toml");
  REQUIRE(machine);
  const auto k = post::make_kinematics(*machine);
  const Joints joints{12.0, -7.0, -20.0, -30.0, 0.0, 40.0};
  const auto pose = k->forward(joints);
  LineEnd end;
  end.words = {pose.tip[0], pose.tip[1], pose.tip[2], -30.0, 0.0, 40.0};
  end.tcp = true;
  const Joints found = machine_joints(*machine, end);
  for (std::size_t i = 0; i < 6; ++i) {
    CHECK(found[i] == Approx(joints[i]).margin(1e-9));
  }
  end.tcp = false;
  CHECK(machine_joints(*machine, end) == end.words);
}

TEST_CASE("the approach: retract along the tool when the position is known, else straight up") {
  const auto machine = post::load_machine_config(source + "/configs/fanuc-xyzac-trt.toml");
  REQUIRE(machine);
  Approach a;
  a.to = {10.0, 5.0, -20.0, -30.0, 0.0, 40.0};
  a.clearance = 2.0;
  SECTION("position unknown on a trunnion: Z up first, nothing else moves") {
    const auto blocks = approach_blocks(*machine, a);
    REQUIRE(blocks.size() == 6);
    CHECK(blocks[0] == "G94");
    CHECK(blocks[1] == "G0 Z200.000");
    CHECK(blocks[2] == "G0 A-30.0000 C40.0000");
    CHECK(blocks.back() == "G1 X10.000 Y5.000 Z-20.000 A-30.0000 C40.0000 F300");
  }
  SECTION("under TCP the approach runs with TCP cancelled") {
    a.tcp = true;
    const auto blocks = approach_blocks(*machine, a);
    CHECK(blocks.front() == "G49");
  }
  SECTION("a known position: the first move is the retract along the tool axis") {
    a.from = Joints{0.0, 0.0, -10.0, 0.0, 0.0, 0.0}; // tool vertical: the retract is +Z
    const auto blocks = approach_blocks(*machine, a);
    CHECK(blocks[1] == "G1 X0.000 Y0.000 Z-8.000 A0.0000 C0.0000 F300");
  }
  CHECK(tool_axis_fixed(*machine));
}

TEST_CASE("a program line that is not G-code words stops a restart, naming it") {
  // A restart found or rebuilt from a line that cannot be read would be a guess.
  TempDir dir;
  const auto file = dir.write("bad.nc", "G21 G90\nG1 X1 (never closed\nG1 X2\n").string();
  const auto window = read_window(file, 1, 3, 0);
  REQUIRE_FALSE(window);
  CHECK(window.error().describe() == file + ":2: comment not closed");
  const auto restore = restore_blocks(file, 2);
  REQUIRE_FALSE(restore);
  CHECK(restore.error().describe() == file + ":2: comment not closed");
  // The window reads the whole program (it counts its lines); the modes are read only up to
  // the restart, so a restart before the bad line restores as it is.
  CHECK(restore_blocks(file, 1).value() == std::vector<std::string>{"G21 G90"});
}
