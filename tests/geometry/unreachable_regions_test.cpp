// Where the ball cannot reach, located: connected groups of blocked vertices, and on a bowl
// narrower than the ball, the one region at its bottom.

#include "geometry/lifted_regions.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/toolpath_planner.hpp"
#include "geometry/unreachable_regions.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>

#include <optional>

using namespace subfeed::geometry;

TEST_CASE("blocked vertices sharing triangle edges form one region, apart, two") {
  // A strip of 8 vertices in two rows: x = 0..3, y = 0 and 1; triangles between them.
  SurfaceMesh mesh;
  for (int row = 0; row < 2; ++row) {
    for (int x = 0; x < 4; ++x) {
      mesh.points.emplace_back(x, row, 0.5 * x);
    }
  }
  for (int x = 0; x < 3; ++x) {
    mesh.triangles.push_back({x, x + 1, x + 5});
    mesh.triangles.push_back({x, x + 5, x + 4});
  }
  SECTION("x = 0 and x = 3 columns blocked: two regions, apart") {
    const std::vector<char> reachable{0, 1, 1, 0, 0, 1, 1, 0};
    const auto regions = unreachable_regions(mesh, reachable);
    REQUIRE(regions.size() == 2);
    CHECK(regions[0].vertices == 2);
    CHECK(regions[1].vertices == 2);
    CHECK(regions[0].centroid.isApprox(Eigen::Vector3d(0.0, 0.5, 0.0)));
    CHECK(regions[1].centroid.isApprox(Eigen::Vector3d(3.0, 0.5, 1.5)));
  }
  SECTION("three columns blocked: one region with its box") {
    const std::vector<char> reachable{0, 0, 0, 1, 0, 0, 0, 1};
    const auto regions = unreachable_regions(mesh, reachable);
    REQUIRE(regions.size() == 1);
    CHECK(regions[0].vertices == 6);
    CHECK(regions[0].low.isApprox(Eigen::Vector3d(0.0, 0.0, 0.0)));
    CHECK(regions[0].high.isApprox(Eigen::Vector3d(2.0, 1.0, 1.0)));
  }
  SECTION("everything reachable: no region") {
    CHECK(unreachable_regions(mesh, std::vector<char>(8, 1)).empty());
  }
}

namespace {

// Where the ball cannot reach is settled before the passes: one deformation solve reaches
// the same code at a fraction of the cost under the sanitizers. The regions' boxes are the
// mesh's vertices: `tolerance` (mm; empty: the plan's own) sets how finely they fall.
PlanSummary summary_under_3mm_ball(const Cage& cage, std::optional<double> tolerance,
                                   std::optional<double> mesh_chord = {}) {
  const auto surface = LimitSurface::build(cage);
  REQUIRE(surface);
  PlanOptions options;
  options.ball_radius = 3.0;
  options.scallop = 0.01;
  options.refine_iterations = 1;
  options.tolerance = tolerance;
  options.mesh_chord = mesh_chord;
  const auto planner = ToolpathPlanner::prepare(cage, *surface, options);
  REQUIRE(planner);
  return planner->summary();
}

} // namespace

TEST_CASE("a bowl narrower than the ball: one region, at its bottom", "[slow]") {
  // z = 0.25 (x^2 + y^2): radius 2 mm at the bottom, growing outward; a 3 mm ball reaches
  // only where the radius across the passes has grown past 3 mm.
  // A 2 um mesh places the region's box well within the checks' 0.1 mm.
  const auto s = summary_under_3mm_ball(subfeed::testing::grid_cage(9, 2.0, 0.25, 0.25), 0.002);
  REQUIRE(s.unreachable_vertices > 0);
  REQUIRE(s.unreachable_regions.size() == 1);
  const auto& r = s.unreachable_regions.front();
  CHECK(r.vertices == s.unreachable_vertices);
  CHECK(std::abs(r.centroid.x()) < 0.05);
  CHECK(std::abs(r.centroid.y()) < 1.0);
  CHECK(r.low.x() < 0.0);
  CHECK(r.high.x() > 0.0);
  // The bowl is round: the ball misses it as far along the passes as across them.
  const Eigen::Vector3d size = r.high - r.low;
  CHECK(std::abs(size.x() - size.y()) < 0.1);
}

TEST_CASE("a trough narrower than the ball along the passes is found too", "[slow]") {
  // z = 0.25 x^2, flat along y; the passes run along x (planes across y), so the radius
  // across them is infinite, but along them it is 2 mm at the bottom: a 3 mm ball misses
  // the strip where 0.5 / (1 + x^2 / 4)^1.5 >= 1/3, |x| <= 1.114 mm, the trough's length.
  // The strip's edge falls within a cell of the planner's mesh: at its default chord (H/4)
  // cells across the trough's bottom are 0.2 mm, so a 0.4 um chord is asked for to place it
  // within 0.1 mm.
  const auto s =
      summary_under_3mm_ball(subfeed::testing::grid_cage(9, 2.0, 0.25, 0.0), {}, 4e-4);
  REQUIRE(s.unreachable_regions.size() == 1);
  const auto& r = s.unreachable_regions.front();
  CHECK(r.high.x() == Approx(1.114).margin(0.1));
  CHECK(r.low.x() == Approx(-1.114).margin(0.1));
  CHECK(r.high.y() - r.low.y() > 10.0);
}

TEST_CASE("the material a bowl narrower than the ball keeps at its bottom, exactly", "[slow]") {
  // z = a rho^2 has radius 1/(2a) at its bottom. A ball of radius r > 1/(2a) set on the axis
  // touches the walls at rho^2 = r^2 - 1/(4a^2) and stays a (r - 1/(2a))^2 above the bottom:
  // that is the material left there. (A cage sampling a quadratic has the same quadratic,
  // raised by a constant, as its limit surface.)
  struct Bowl {
    double a, r;
  };
  for (const auto [a, r] : {Bowl{0.25, 3.0}, Bowl{0.5, 2.0}, Bowl{0.5, 3.0}, Bowl{1.0, 2.0}}) {
    CAPTURE(a, r);
    const auto cage = subfeed::testing::grid_cage(9, 2.0, a, a);
    const auto surface = LimitSurface::build(cage);
    REQUIRE(surface);
    PlanOptions options;
    options.ball_radius = r;
    options.scallop = 0.01;
    options.tolerance = 0.005;
    options.refine_iterations = 1; // what the ball leaves does not depend on the passes
    const auto planner = ToolpathPlanner::prepare(cage, *surface, options);
    REQUIRE(planner);
    const auto& s = planner->summary();
    REQUIRE_FALSE(s.unreachable_regions.empty());
    const double exact = a * (r - 0.5 / a) * (r - 0.5 / a);
    CHECK(s.unreachable_regions.front().material_mm == Approx(exact).margin(0.01 * exact + 0.004));
    CHECK(s.scallop == 0.01);
  }
}

TEST_CASE("lifted CL points group by distance, thickest region first") {
  std::vector<LiftedPoint> points;
  for (int i = 0; i < 5; ++i) { // a row 0.5 mm apart: one region
    points.push_back({Eigen::Vector3d(0.5 * i, 0.0, 0.0), 0.01 * (i + 1)});
  }
  points.push_back({Eigen::Vector3d(20.0, 0.0, 1.0), 0.2}); // far away: a region of its own
  points.push_back({Eigen::Vector3d(20.4, 0.3, 1.0), 0.1});
  const auto regions = lifted_regions(points, 1.0);
  REQUIRE(regions.size() == 2);
  CHECK(regions[0].points == 2);
  CHECK(regions[0].max_lift_mm == 0.2);
  CHECK(regions[0].centroid.isApprox(Eigen::Vector3d(20.2, 0.15, 1.0)));
  CHECK(regions[1].points == 5);
  CHECK(regions[1].max_lift_mm == Approx(0.05));
  CHECK(regions[1].low.isApprox(Eigen::Vector3d(0.0, 0.0, 0.0)));
  CHECK(regions[1].high.isApprox(Eigen::Vector3d(2.0, 0.0, 0.0)));
  CHECK(lifted_regions({}, 1.0).empty());
}
