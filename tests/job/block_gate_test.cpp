// The gate on posted blocks (job/block_gate.hpp): what the machine does between two poses
// that the CL path's gate cannot see, measured through the machine's own kinematics.

#include "geometry/limit_surface.hpp"
#include "geometry/motion_gate.hpp"
#include "geometry/obj_reader.hpp"
#include "job/block_gate.hpp"
#include "post/machine_config.hpp"

#include <catch2/catch.hpp>
#include <initializer_list>
#include <utility>

using namespace subfeed;

namespace {

const std::string gate_test_dir = SUBFEED_SOURCE_DIR;

// The plane z = 0 over |x|, |y| <= 20 mm, gated for a 6 mm ball; with `floor`, the whole
// (default) tool and a floor at z = 0.
geometry::MotionGate gated_plane(bool floor = false) {
  const auto cage = geometry::read_obj(gate_test_dir + "/examples/plane.obj");
  REQUIRE(cage);
  const auto surface = geometry::LimitSurface::build(*cage);
  REQUIRE(surface);
  geometry::GateOptions options{3.0, 0.003, floor, geometry::ToolAssembly::ball_only(3.0), {}};
  if (floor) {
    options.fixture.floor_z = 0.0;
  }
  auto gate = geometry::MotionGate::build(*cage, *surface, options);
  REQUIRE(gate);
  return std::move(*gate);
}

// A block moving the words given: {axis, value}, axes X Y Z A B C numbered 0 to 5.
post::MotionBlock posted_block(post::Motion motion,
                               std::initializer_list<std::pair<std::size_t, double>> words) {
  post::MotionBlock b;
  b.motion = motion;
  for (const auto& [axis, value] : words) {
    b.axes[axis] = value;
  }
  b.feed = 1000.0;
  b.cl_line = 7;
  return b;
}

} // namespace

TEST_CASE("posted blocks: a head that swings its tool through the part, or under the table, "
          "on a rapid is refused, though the straight move between the two poses clears them") {
  const auto machine =
      post::load_machine_config(gate_test_dir + "/configs/grblhal-xyzac-head.toml");
  REQUIRE(machine);
  const auto kinematics = post::make_kinematics(*machine);
  const auto pose = [&](double z, double a) {
    const auto p = kinematics->forward({0, 0, z, a, 0, 0});
    cl::ClPose c;
    c.tip = p.tip;
    c.axis = p.axis;
    c.kind = cl::MoveKind::rapid;
    return c;
  };
  // The tip 170 mm below the pivot. Pivot 169.5 mm over the plane's middle: at A = -60 and
  // +60 the tip is 84.5 mm up and 147 mm to either side, but the joints pass A = 0 on the
  // way, the ball's bottom 0.5 mm under the plane. Pivot 100 mm up: 70 mm under the table.
  for (const bool table : {false, true}) {
    const double z = table ? 100.0 : 169.5;
    INFO((table ? "under the table" : "through the part"));
    CHECK(pose(z, -60).tip[2] == Approx(z - 85.0).margin(1e-9));
    auto straight = gated_plane(table);
    CHECK(straight.check(pose(z, -60)));
    CHECK(straight.check(pose(z, 60))); // what a gate on the CL poses alone lets through
    job::BlockGate gate(*machine, gated_plane(table));
    CHECK(gate.check(posted_block(post::Motion::rapid, {{3, -60.0}, {5, 0.0}}))); // XYZ unknown
    CHECK(gate.check(posted_block(post::Motion::rapid, {{0, 0.0}, {1, 0.0}, {2, z}})));
    CHECK(gate.check(posted_block(post::Motion::rapid, {{3, -58.0}}))); // clear
    const auto swing = gate.check(posted_block(post::Motion::rapid, {{3, 60.0}}));
    REQUIRE_FALSE(swing);
    CHECK(swing.error().message.starts_with("as posted, the joints moving from block to block: "));
    CHECK(swing.error().message.find(table ? "below the stock" : "rapid") != std::string::npos);
    CHECK(swing.error().where.line == 7);
  }
}

TEST_CASE("posted blocks on a three-axis router: a feed on the surface passes, one cutting "
          "below the post's tolerance is refused, a rapid into the part is refused") {
  const auto machine = post::load_machine_config(gate_test_dir + "/configs/grbl-router-3axis.toml");
  REQUIRE(machine);
  job::BlockGate gate(*machine, gated_plane());
  CHECK(gate.check(posted_block(post::Motion::rapid, {{0, -10.0}, {1, 0.0}, {2, 10.0}})));
  CHECK(gate.check(posted_block(post::Motion::linear, {{2, 0.0}})));
  CHECK(gate.check(posted_block(post::Motion::linear, {{0, 10.0}, {2, -0.002}}))); // within 3 um
  CHECK_FALSE(gate.check(posted_block(post::Motion::linear, {{0, -10.0}, {2, -0.01}})));
  CHECK(gate.check(posted_block(post::Motion::linear, {{2, 5.0}})));
  // The tip is the ball's bottom: 1 mm under the plane.
  CHECK_FALSE(gate.check(posted_block(post::Motion::rapid, {{0, 5.0}, {1, 5.0}, {2, -1.0}})));
}
