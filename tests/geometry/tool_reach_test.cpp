// The tool's reach (tool_reach.hpp) on parts with exact answers: closed boxes whose underside
// no tool from above reaches, and a plate standing over a floor, whose shadow a ball drawn
// back upward cannot leave. Measured on the plan itself: every pose's axis, every floor
// pose's distance from the plate, and the area left against an independent integral.

#include "geometry/limit_surface.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/step_over.hpp"
#include "geometry/tool_reach.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/grid_cage.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <sstream>

using namespace subfeed;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

struct Plan {
  geometry::PlanSummary summary;
  std::vector<cl::ClPose> poses;
};

Plan plan(const geometry::Cage& cage, const geometry::PlanOptions& options) {
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  auto planner = geometry::ToolpathPlanner::prepare(cage, *surface, options);
  REQUIRE(planner);
  Plan out;
  const auto ran = planner->run([&](const cl::ClPose& p) -> Expected<void> {
    out.poses.push_back(p);
    return {};
  });
  if (!ran) {
    FAIL(ran.error().message);
  }
  out.summary = planner->summary();
  return out;
}

// The unit cube's cage stretched to sx x sy x sz mm, standing on z = 0.
geometry::Cage box(double sx, double sy, double sz) {
  auto cage = subfeed::testing::cube_cage();
  for (auto& p : cage.positions) {
    p = Eigen::Vector3d(p.x() * sx, p.y() * sy, (p.z() + 0.5) * sz);
  }
  return cage;
}

// The limit surface's area whose normal leans more than `angle_deg` from +Z, integrated on
// its own fine tessellation (not the planner's mesh), mm^2.
double area_beyond(const geometry::Cage& cage, double angle_deg) {
  const auto surface = geometry::LimitSurface::build(cage);
  REQUIRE(surface);
  double area = 0.0;
  for (int f = 0; f < surface->face_count(); ++f) {
    const auto tess = surface->tessellate(f, 96);
    for (const auto& t : tess.triangles) {
      std::array<Eigen::Vector3d, 3> p;
      Eigen::Vector2d centre = Eigen::Vector2d::Zero();
      for (std::size_t k = 0; k < 3; ++k) {
        const auto& uv = tess.uv[static_cast<std::size_t>(t[k])];
        p[k] = surface->evaluate_regular(f, uv.x(), uv.y())->point;
        centre += uv / 3.0;
      }
      const auto s = surface->evaluate_regular(f, centre.x(), centre.y());
      if (!s) {
        FAIL(s.error().message); // no assertion per triangle: they would cost more than this
      }
      if (std::acos(std::clamp(s->normal.z(), -1.0, 1.0)) > angle_deg * deg) {
        area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
      }
    }
  }
  return area;
}

double left_area(const geometry::PlanSummary& s) {
  double area = 0.0;
  for (const auto& r : s.out_of_reach) {
    area += r.area_mm2;
  }
  return area;
}

geometry::PlanOptions options(double r, bool fixed_axis, double max_tilt_deg) {
  geometry::PlanOptions o;
  o.ball_radius = r;
  o.scallop = 0.05;
  o.tolerance = 0.002;
  o.fixed_axis = fixed_axis;
  o.max_tilt_deg = max_tilt_deg;
  o.refine_iterations = 8;
  return o;
}

// A floor 60 x 60 mm at z = 0 and a plate a x a mm at `height` over its middle, both flat,
// their boundaries and corners kept (interpolateboundary edge and corner).
geometry::Cage plate_over_floor(double a, double height) {
  std::ostringstream obj;
  constexpr int n = 5;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      obj << "v " << -30 + 15 * i << ' ' << -30 + 15 * j << " 0\n";
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i + 1;
      obj << "f " << v << ' ' << v + 1 << ' ' << v + n + 1 << ' ' << v + n << '\n';
    }
  }
  const double h = a / 2;
  obj << "v " << -h << ' ' << -h << ' ' << height << "\nv " << h << ' ' << -h << ' ' << height
      << "\nv " << h << ' ' << h << ' ' << height << "\nv " << -h << ' ' << h << ' ' << height
      << "\nf 26 27 28 29\nt interpolateboundary 1/0/0 2\n";
  std::istringstream in(obj.str());
  auto cage = geometry::parse_obj(in, "plate-over-floor");
  REQUIRE(cage);
  return std::move(*cage);
}

// The distance in XY from (x, y) to the square [-h, h]^2 (0 inside).
double to_square(double x, double y, double h) {
  return std::hypot(std::max(std::abs(x) - h, 0.0), std::max(std::abs(y) - h, 0.0));
}

} // namespace

TEST_CASE("within_tilt turns an axis toward +Z in its own vertical plane, no further than the "
          "limit",
          "[unit]") {
  for (const double limit : {0.0, 20.0, 45.0, 90.0, 120.0}) {
    for (int k = 0; k < 24; ++k) {
      for (const double tilt : {0.0, 10.0, 44.0, 89.0, 91.0, 135.0, 180.0}) {
        const double azimuth = k * 15.0 * deg;
        const Eigen::Vector3d axis(std::sin(tilt * deg) * std::cos(azimuth),
                                   std::sin(tilt * deg) * std::sin(azimuth), std::cos(tilt * deg));
        const auto turned = geometry::within_tilt(axis, limit);
        INFO("limit " << limit << ", tilt " << tilt << ", azimuth " << k * 15);
        CHECK(turned.norm() == Approx(1.0));
        const double got = std::acos(std::clamp(turned.z(), -1.0, 1.0)) / deg;
        CHECK(got == Approx(std::min(tilt, limit)).margin(1e-9));
        if (tilt > limit && tilt < 180.0 && limit > 0.0) {
          // Same vertical half-plane: the horizontal part keeps its direction.
          CHECK(std::atan2(turned.y(), turned.x()) == Approx(std::atan2(axis.y(), axis.x())));
        }
      }
    }
  }
}

namespace {

struct BoxCase {
  double sx, sy, sz, r;
};

// A closed box planned at `tilt` (or with a vertical tool): no axis leans past the tilt,
// and the area left is the exact area beyond it plus at most a band of mesh cells.
void check_closed_part(const BoxCase& c, bool fixed, double tilt) {
  INFO(c.sx << " x " << c.sy << " x " << c.sz << " mm, ball r " << c.r << ", "
            << (fixed ? "fixed axis" : "tilt " + std::to_string(tilt)));
  const auto cage = box(c.sx, c.sy, c.sz);
  const auto p = plan(cage, options(c.r, fixed, tilt));
  const double limit = fixed ? 90.0 : tilt;
  CHECK(p.summary.reach_angle_deg == limit);
  // The lowest axis of all (one check: a check per pose costs more than the plan).
  double lowest = 1.0;
  for (const auto& pose : p.poses) {
    lowest = std::min(lowest, pose.axis[2]);
  }
  CHECK(lowest >= (fixed ? 1.0 : std::cos(limit * deg) - 1e-9));
  // Every left triangle has a vertex beyond the limit, so the area left exceeds the exact
  // one by at most a band one mesh cell wide round it.
  const double exact = area_beyond(cage, limit);
  const double left = left_area(p.summary);
  CHECK(left >= 0.995 * exact);
  CHECK(left <= 1.03 * exact);
  REQUIRE_FALSE(p.summary.out_of_reach.empty());
  for (const auto& region : p.summary.out_of_reach) {
    CHECK(region.steepest_deg > limit);
    CHECK(region.hidden == 0);
  }
}

} // namespace

TEST_CASE("a closed part is planned on its upper side: no axis leans past the tilt, and the "
          "rest is reported by its area",
          "[parts][slow]") {
  // Boxes of several proportions and sizes, tilts from 35 to 90 degrees, both axis modes.
  for (const auto& c : {BoxCase{20, 20, 20, 2}, BoxCase{30, 14, 10, 1.5}, BoxCase{12, 24, 18, 3}}) {
    check_closed_part(c, true, 90.0); // a vertical tool reaches 90 degrees whatever the tilt
    for (const double tilt : {90.0, 60.0, 35.0}) {
      check_closed_part(c, false, tilt);
    }
  }
}

TEST_CASE("a closed box planned at a 60 degree tilt leaves exactly what leans further", "[unit]") {
  check_closed_part({16, 16, 12, 2}, false, 60.0); // the family's check, on one small box
}

namespace {

// The plan of a plate over a floor: no floor pose where the ball could not rise past the
// plate, the floor cut up to the shadow, and the shadow reported as what is left.
void check_plate(double a, double height, double r, bool fixed) {
  INFO("plate " << a << " mm at " << height << " mm, ball r " << r
                << (fixed ? ", fixed axis" : ", axis along the normal"));
  const auto p = plan(plate_over_floor(a, height), options(r, fixed, 90.0));
  const double margin = 1e-3; // the gate's tolerance at this mesh
  // A cell's diagonal: cells are at most two flat step-overs on a side.
  const double cell = 2.0 * std::sqrt(2.0) * geometry::flat_step(r, 0.05);
  double nearest = 1e9;
  for (const auto& pose : p.poses) {
    if (pose.kind == cl::MoveKind::feed && pose.tip[2] < 1e-3) {
      nearest = std::min(nearest, to_square(pose.tip[0], pose.tip[1], a / 2));
    }
  }
  // No floor pose nearer the plate's outline than r, and the floor cut up to the shadow,
  // within a cell of it.
  CHECK(nearest >= r - margin);
  CHECK(nearest <= r + cell);
  // The shadow: the plate grown by r, its corners rounded.
  const double exact = a * a + 4 * a * r + std::numbers::pi * r * r;
  // The left triangles reach at most a cell's diagonal past the shadow's edge.
  const double band = (4 * a + 2 * std::numbers::pi * r) * cell;
  REQUIRE(p.summary.out_of_reach.size() == 1);
  const auto& region = p.summary.out_of_reach.front();
  CHECK(region.area_mm2 >= exact);
  CHECK(region.area_mm2 <= exact + band);
  CHECK(region.hidden > 0);
  CHECK(region.tilted == 0);
  CHECK(region.centroid.norm() < 0.1);
}

} // namespace

TEST_CASE("the floor under a plate is left uncut: no ball stands where it could not be drawn "
          "back up past the plate",
          "[parts][slow]") {
  for (const double a : {12.0, 20.0}) {
    for (const double height : {8.0, 20.0}) {
      for (const double r : {1.5, 2.0, 3.0}) {
        for (const bool fixed : {false, true}) {
          check_plate(a, height, r, fixed);
        }
      }
    }
  }
}

TEST_CASE("the floor under one plate is left uncut, with either axis", "[unit]") {
  for (const bool fixed : {false, true}) {
    check_plate(12.0, 8.0, 2.0, fixed); // the family's check, on one plate
  }
}
