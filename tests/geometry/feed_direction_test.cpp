// The feed direction chosen by predicted path length, on grid troughs whose limit surfaces
// are exact (z = b y^2 runs along X, z = a x^2 along Y): passes along a trough are spaced
// across its concave curve, where the ball leaves a smaller scallop at a given step
// (docs/METHOD.md §5: 2.70e-2 against 3.61e-2 flat), passes across it along the flat, so the
// path along the trough is the shorter one.

#include "geometry/limit_surface.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/grid_cage.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <numbers>

using namespace subfeed;

namespace {

geometry::PlanOptions trough_options() {
  geometry::PlanOptions o;
  o.ball_radius = 3.0;
  o.scallop = 0.01;
  o.tolerance = 0.001;
  return o;
}

// The planner's summary after a whole plan (cutting length included).
geometry::PlanSummary planned(const geometry::Cage& cage, const geometry::PlanOptions& o) {
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  auto planner = geometry::ToolpathPlanner::prepare(cage, *surface, o);
  REQUIRE(planner);
  REQUIRE(planner->run([](const cl::ClPose&) -> Expected<void> { return {}; }));
  return planner->summary();
}

} // namespace

TEST_CASE("auto feed direction: along a trough, whichever way it runs", "[slow]") {
  const bool along_x = GENERATE(true, false);
  CAPTURE(along_x);
  const auto cage = along_x ? subfeed::testing::grid_cage(6, 5.0, 0.0, 0.05)
                            : subfeed::testing::grid_cage(6, 5.0, 0.05, 0.0);
  auto o = trough_options();
  o.choose_direction = true;
  const auto chosen = planned(cage, o);
  CHECK(chosen.direction_deg == (along_x ? 0.0 : 90.0));
  REQUIRE(chosen.direction_prices.size() == 6);
  CHECK(chosen.direction_prices[0].direction_deg == 0.0);
  CHECK(chosen.direction_prices[2].direction_deg == 90.0);
  o.choose_direction = false;
  o.direction_deg = along_x ? 90.0 : 0.0; // across the trough
  const auto across = planned(cage, o);
  INFO("along " << chosen.cut_length << " mm, across " << across.cut_length << " mm");
  CHECK(chosen.cut_length < 0.95 * across.cut_length);
  CHECK(across.direction_deg == o.direction_deg);
  CHECK(across.direction_prices.empty());
}

TEST_CASE("auto feed direction: a trough at 45 degrees is cut along it", "[slow]") {
  auto cage = subfeed::testing::grid_cage(6, 5.0, 0.0, 0.05); // along X, then turned
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(std::numbers::pi / 4.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (auto& p : cage.positions) {
    p = turn * p;
  }
  auto o = trough_options();
  o.choose_direction = true;
  // The same mesh for both (a choice that may end in rings is meshed more finely).
  o.mesh_chord = geometry::mesh_chord(o);
  o.min_cell_mm = geometry::min_cell(o);
  const auto chosen = planned(cage, o);
  CHECK(chosen.direction_deg == 45.0);
  // Off the axes, the choice is confirmed by full solves of it and of the cheaper axis, and
  // the plan cuts the winner's full deformation: the same path as asking for 45 degrees.
  REQUIRE(chosen.direction_prices.size() == 8);
  const auto& off_axis = chosen.direction_prices[6];
  const auto& on_axis = chosen.direction_prices[7];
  CHECK_FALSE(chosen.direction_prices[5].full);
  CHECK(off_axis.full);
  CHECK(on_axis.full);
  CHECK(off_axis.direction_deg == 45.0);
  CHECK((on_axis.direction_deg == 0.0 || on_axis.direction_deg == 90.0));
  CHECK(off_axis.predicted_length < on_axis.predicted_length);
  o.choose_direction = false;
  o.direction_deg = 45.0;
  const auto asked = planned(cage, o);
  CHECK(asked.cut_length == chosen.cut_length);
  CHECK(asked.passes == chosen.passes);
}
