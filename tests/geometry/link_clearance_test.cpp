// Links' clearance against a part with exact answers: a flat plate, the square |x|, |y| <= 20
// at z = 0 (a grid cage of flat control points). Every way a climb answers is measured
// again with the whole-tool sweep the motion gate uses, and the way it did not take is
// shown to break the rules, so the test fails if a climb gives up a clear way or takes a
// blocked one.

#include "geometry/assembly_sweep.hpp"
#include "geometry/link_clearance.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/surface_mesh.hpp"
#include "support/grid_cage.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace subfeed;
using geometry::AssemblyClearance;
using geometry::Fixture;
using geometry::LinkClearance;
using geometry::ToolAssembly;

namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double safe_z = 50.0;

ToolAssembly plate_tool() {
  return {.ball_radius = 3, .flute_length = 18, .shank_diameter = 6, .stickout = 40, .holder = {}};
}

struct Plate {
  geometry::Cage cage = subfeed::testing::grid_cage(9, 5.0, 0.0, 0.0);
  geometry::SurfaceMesh mesh;
  std::unique_ptr<geometry::TriangleTree> tree;
  std::unique_ptr<geometry::LimitDistance> exact;

  Plate() {
    auto surface = geometry::LimitSurface::build(cage);
    REQUIRE(surface);
    auto m = geometry::mesh_surface(cage, *surface, 8);
    REQUIRE(m);
    mesh = std::move(*m);
    tree = std::make_unique<geometry::TriangleTree>(mesh.points, mesh.triangles);
    auto e = geometry::LimitDistance::build(cage);
    REQUIRE(e);
    exact = std::make_unique<geometry::LimitDistance>(std::move(*e));
  }
  [[nodiscard]] LinkClearance links() const {
    return {*exact, 3.0, true, plate_tool(), Fixture{}, *tree};
  }
  // The gate's rules with the links' margin: what a climb's answer must keep.
  [[nodiscard]] bool sweeps_clear(const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                  const Eigen::Vector3d& axis) const {
    Fixture f;
    f.clearance_min += LinkClearance::body_margin_mm;
    const AssemblyClearance clearance(plate_tool(), f, *tree);
    return !geometry::sweep_move(clearance, t0, axis, t1, axis, {}, nullptr).first &&
           !exact->nearest(t0 + 3.0 * axis, t1 + 3.0 * axis, 3.0);
  }
};

Eigen::Vector3d leaning(double tilt_deg, double toward_deg) {
  return {std::sin(tilt_deg * deg) * std::cos(toward_deg * deg),
          std::sin(tilt_deg * deg) * std::sin(toward_deg * deg), std::cos(tilt_deg * deg)};
}

} // namespace

TEST_CASE("a climb over the open plate goes straight up", "[unit]") {
  const Plate plate;
  const auto links = plate.links();
  for (const double tilt : {0.0, 20.0, 40.0}) {
    for (const double toward : {0.0, 90.0, 225.0}) {
      const Eigen::Vector3d axis = leaning(tilt, toward);
      const Eigen::Vector3d from = Eigen::Vector3d(-5.0, 7.0, 0.0) + 5.0 * axis;
      const auto way = links.climb(from, axis, safe_z);
      REQUIRE(way);
      REQUIRE(way->size() == 1);
      CHECK(way->front().isApprox(Eigen::Vector3d(from.x(), from.y(), safe_z)));
    }
  }
}

TEST_CASE("a tilted tool under the plate's edge climbs back along its axis, not up", "[unit]") {
  const Plate plate;
  const auto links = plate.links();
  // The tip under the plate, the tool leaning out past its edge at x = 20: straight up,
  // the shank sweeps back into the edge; along the axis the tool comes out beside it.
  for (const double x : {12.0, 15.0, 18.0}) {
    for (const double tilt : {30.0, 40.0}) {
      for (const double z : {-30.0, -24.0}) {
        CAPTURE(x, tilt, z);
        const Eigen::Vector3d axis = leaning(tilt, 0.0);
        const Eigen::Vector3d from(x, 2.0, z);
        const Eigen::Vector3d up(x, 2.0, safe_z);
        REQUIRE(plate.sweeps_clear(from, from, axis)); // the pose itself keeps the rules
        CHECK_FALSE(plate.sweeps_clear(from, up, axis));
        const auto way = links.climb(from, axis, safe_z);
        REQUIRE(way);
        REQUIRE(way->size() == 2);
        CHECK(plate.sweeps_clear(from, way->front(), axis));
        CHECK(plate.sweeps_clear(way->front(), way->back(), axis));
        CHECK(way->back().z() == Approx(safe_z));
        CHECK((way->front() - from).normalized().isApprox(axis, 1e-9));
      }
    }
  }
}

TEST_CASE("a tool buried under the plate has no climb out", "[unit]") {
  const Plate plate;
  const auto links = plate.links();
  for (const double tilt : {0.0, 10.0}) {
    const Eigen::Vector3d axis = leaning(tilt, 45.0);
    const Eigen::Vector3d from(0.0, 0.0, -45.0);
    REQUIRE(plate.sweeps_clear(from, from, axis));
    CHECK_FALSE(links.climb(from, axis, safe_z));
  }
}

TEST_CASE("feed clearance spent over many short moves refuses what a sweep of each refuses",
          "[unit]") {
  const Plate plate;
  const auto links = plate.links();
  Fixture f;
  f.clearance_min += LinkClearance::body_margin_mm;
  const AssemblyClearance clearance(plate_tool(), f, *plate.tree);
  // Tips stepping 0.05 mm toward the plate's edge under it, the axis turning as they go:
  // the shank meets the edge somewhere along the runs that go far enough.
  for (const double tilt_end : {30.0, 22.0, 12.0}) {
    for (const double x_end : {20.0, 17.0, 14.0}) {
      CAPTURE(tilt_end, x_end);
      std::vector<Eigen::Vector3d> tips, axes;
      const int steps = static_cast<int>(std::round((24.0 - x_end) / 0.05));
      for (int i = 0; i <= steps; ++i) {
        const double t = static_cast<double>(i) / steps;
        tips.emplace_back(24.0 - t * (24.0 - x_end), 0.0, -25.0);
        axes.push_back(leaning(30.0 + t * (tilt_end - 30.0), 0.0));
      }
      bool swept = true;
      for (std::size_t i = 0; i + 1 < tips.size() && swept; ++i) {
        swept = !geometry::sweep_move(clearance, tips[i], axes[i], tips[i + 1], axes[i + 1], {},
                                      nullptr)
                     .first;
      }
      CHECK(links.feed_clear(tips, axes) == swept);
    }
  }
}
