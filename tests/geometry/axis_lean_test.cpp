// Lead and tilt (geometry/axis_lean.hpp): the leaned axis against exact vectors, the feed
// direction along a known curve, the fractions where a rule stops the full lean; and whole
// plans over exact grid surfaces in every pattern, measured against the exact normal at
// each contact: the lean is what was asked, its sign follows the feed, and the scallop and
// gouge are those of the unleaned path (the ball's centre does not move).

#include "cl/cl_writer.hpp"
#include "geometry/axis_lean.hpp"
#include "geometry/limit_surface.hpp"
#include "geometry/path_verifier.hpp"
#include "geometry/toolpath_planner.hpp"
#include "support/grid_cage.hpp"
#include "support/temp_dir.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace subfeed;
using geometry::AxisLean;

namespace {

constexpr double lean_deg_rad = std::numbers::pi / 180.0;

double lean_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / lean_deg_rad;
}

} // namespace

TEST_CASE("lean: a vertical axis fed along +X leads toward +X and tilts toward +Y (left)") {
  const Eigen::Vector3d z(0, 0, 1), x(1, 0, 0);
  const auto led = geometry::leaned_axis(z, x, {15.0, 0.0}, 1.0);
  CHECK(
      (led - Eigen::Vector3d(std::sin(15 * lean_deg_rad), 0, std::cos(15 * lean_deg_rad))).norm() <
      1e-12);
  const auto lag = geometry::leaned_axis(z, x, {-15.0, 0.0}, 1.0);
  CHECK(lag.x() < 0.0);
  const auto tilted = geometry::leaned_axis(z, x, {0.0, 10.0}, 1.0);
  CHECK((tilted - Eigen::Vector3d(0, std::sin(10 * lean_deg_rad), std::cos(10 * lean_deg_rad)))
            .norm() < 1e-12);
  const auto half = geometry::leaned_axis(z, x, {20.0, 0.0}, 0.5);
  CHECK(lean_angle_deg(half, z) == Approx(10.0).margin(1e-9));
  // A feed along the axis has no direction to lean in; fraction 0 leaves it alone.
  CHECK(geometry::leaned_axis(z, z, {15.0, 10.0}, 1.0) == z);
  CHECK(geometry::leaned_axis(z, x, {15.0, 10.0}, 0.0) == z);
}

TEST_CASE("lean: for any axis and feed, the turn is acos(cos L cos T), ahead and left as signed") {
  const double leans[][2] = {{15, 0}, {0, -10}, {-10, 10}, {30, 20}, {-45, -45}};
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(std::sin(k * 0.7), std::cos(k * 1.3), 1.5 + std::sin(k * 0.4)).normalized();
    const Eigen::Vector3d feed(std::cos(k * 0.9), std::sin(k * 0.9), 0.3 * std::sin(k * 2.1));
    const auto& l = leans[k % 5];
    const AxisLean lean{l[0], l[1]};
    const auto a = geometry::leaned_axis(axis, feed, lean, 1.0);
    INFO("k " << k);
    CHECK(a.norm() == Approx(1.0).margin(1e-12));
    CHECK(lean_angle_deg(a, axis) ==
          Approx(std::acos(std::cos(l[0] * lean_deg_rad) * std::cos(l[1] * lean_deg_rad)) /
                 lean_deg_rad)
              .margin(1e-7));
    const Eigen::Vector3d ahead = (feed - feed.dot(axis) * axis).normalized();
    const Eigen::Vector3d left = axis.cross(ahead);
    CHECK(a.dot(left) == Approx(std::sin(l[1] * lean_deg_rad)).margin(1e-12));
    CHECK(std::atan2(a.dot(ahead), a.dot(axis)) / lean_deg_rad == Approx(l[0]).margin(1e-7));
  }
}

TEST_CASE("lean: the feed direction along a circle is its tangent, ends included") {
  for (const double radius : {2.0, 10.0, 50.0}) {
    std::vector<Eigen::Vector3d> at;
    for (int i = 0; i <= 200; ++i) {
      const double t = i * 0.01; // radians
      at.emplace_back(radius * std::cos(t), radius * std::sin(t), 1.0);
    }
    const auto dirs = geometry::feed_directions(at, 1.5);
    for (std::size_t i = 0; i < at.size(); ++i) {
      const double t = static_cast<double>(i) * 0.01;
      const Eigen::Vector3d tangent(-std::sin(t), std::cos(t), 0.0);
      INFO("radius " << radius << ", point " << i);
      // 1.5 mm either way: the chord's direction, within half the arc's turn of the tangent.
      CHECK(lean_angle_deg(dirs[i], tangent) <= 1.5 / radius / lean_deg_rad + 1e-6);
    }
  }
}

TEST_CASE("lean: fractions are whole where the rules allow, stepped and ramped where they do not, "
          "and every one kept") {
  std::vector<Eigen::Vector3d> at;
  for (int i = 0; i <= 400; ++i) {
    at.emplace_back(i * 0.05, 0.0, 0.0); // 20 mm, 0.05 mm apart
  }
  const AxisLean lean{20.0, 0.0,
                      2.0}; // 2 lean_deg_rad/mm of a 20 lean_deg_rad lean: 0.1 of it a mm
  // Between x = 8 and 10 mm at most a quarter of the lean keeps the rules; at 15 mm none.
  const auto keeps = [&](std::size_t i, double f) {
    REQUIRE(f > 0.0); // none is the caller's axis: never asked
    const double x = at[i].x();
    if (std::abs(x - 15.0) < 0.01) {
      return false;
    }
    return !(x >= 8.0 && x <= 10.0) || f <= 0.25 + 1e-12;
  };
  const auto f = geometry::lean_fractions(at, lean, keeps);
  REQUIRE(f.size() == at.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double x = at[i].x();
    INFO("x " << x << " mm, fraction " << f[i]);
    CHECK((f[i] == 0.0 || keeps(i, f[i])));
    if (i > 0) { // the ramp: a tenth of the lean a millimetre
      CHECK(std::abs(f[i] - f[i - 1]) <= 0.1 * 0.05 + 1e-9);
    }
    if (x < 8.0 - 7.5 - 1e-9 || (x > 10.0 + 7.5 + 1e-9 && x < 15.0 - 10.0)) {
      CHECK(f[i] == 1.0);
    }
  }
  CHECK(f[0] == 1.0);
  CHECK(f[300] == 0.0);                       // x = 15
  CHECK(f[180] == Approx(0.25).margin(1e-9)); // x = 9
  CHECK(f[400] == Approx(0.5).margin(1e-9));  // 5 mm past the stop, ramped back halfway
  const auto all = geometry::lean_fractions(at, lean, [](std::size_t, double) { return true; });
  CHECK(std::ranges::all_of(all, [](double v) { return v == 1.0; }));
}

namespace {

struct LeanCase {
  const char* shape;
  double a, b; // z = a x^2 + b y^2 on the interior faces
  const char* pattern;
  double direction_deg; // < 0: concentric
  double lead, tilt;
};

// The exact normal at the contact under a ball of radius r centred at `c` on
// z = a x^2 + b y^2 (+ a lift): the contact is c - r n, n the normal there.
Eigen::Vector3d normal_under(const Eigen::Vector3d& c, double r, double a, double b) {
  double x = c.x(), y = c.y();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  for (int k = 0; k < 50; ++k) {
    n = Eigen::Vector3d(-2 * a * x, -2 * b * y, 1.0).normalized();
    x = c.x() - r * n.x();
    y = c.y() - r * n.y();
  }
  return n;
}

} // namespace

TEST_CASE("lean on exact surfaces, every pattern: the lead and tilt asked for, signed by the feed, "
          "with the unleaned path's scallop and no gouge",
          "[parts][slow]") {
  const LeanCase cases[] = {
      {"dome", -0.03, -0.02, "x", 0.0, 15.0, 0.0},
      {"dome", -0.03, -0.02, "y", 90.0, 0.0, -10.0},
      {"dome", -0.03, -0.02, "30 lean_deg_rad", 30.0, -10.0, 10.0},
      {"dome", -0.03, -0.02, "concentric", -1.0, 15.0, 0.0},
      {"saddle", 0.02, -0.03, "x", 0.0, -10.0, 10.0},
      {"saddle", 0.02, -0.03, "y", 90.0, 15.0, 0.0},
      {"saddle", 0.02, -0.03, "30 lean_deg_rad", 30.0, 0.0, -10.0},
      {"bowl", 0.03, 0.02, "x", 0.0, 0.0, -10.0},
      {"bowl", 0.03, 0.02, "30 lean_deg_rad", 30.0, 15.0, 0.0},
      {"bowl", 0.03, 0.02, "concentric", -1.0, -10.0, 10.0},
  };
  constexpr double z0 = 20.0, r = 3.0, h = 0.03;
  for (const auto& c : cases) {
    INFO(c.shape << ", " << c.pattern << ", lead " << c.lead << ", tilt " << c.tilt);
    const auto cage = testing::lifted(testing::grid_cage(9, 2.5, c.a, c.b), z0);
    auto surface = geometry::LimitSurface::build(cage);
    REQUIRE(surface);
    geometry::PlanOptions options;
    options.ball_radius = r;
    options.scallop = h;
    if (c.direction_deg < 0.0) {
      options.pattern = geometry::PassPattern::concentric;
    } else {
      options.direction_deg = c.direction_deg;
    }
    options.lean = {c.lead, c.tilt};
    options.stay_down = 0.0; // every feed move on a pass: links retract
    auto planner = geometry::ToolpathPlanner::prepare(cage, *surface, options);
    REQUIRE(planner);
    const testing::TempDir dir;
    const auto file = dir.path() / "lean.cl";
    auto writer = cl::ClWriter::create(file, {"PART", {2 * r, r}, true, {}, {}});
    REQUIRE(writer);
    std::vector<cl::ClPose> poses;
    REQUIRE(planner->run([&](const cl::ClPose& p) -> Expected<void> {
      writer->write(p);
      poses.push_back(p);
      return {};
    }));
    REQUIRE(writer->finish());
    const auto& lean = planner->summary().lean;
    CHECK(lean.points > 0);
    CHECK(lean.full == lean.points); // nothing stops a lean on these gentle parts
    // Each cutting pose inside the exact region, against the exact normal at its contact.
    long measured = 0, as_asked = 0;
    for (std::size_t i = 1; i + 1 < poses.size(); ++i) {
      const auto& p = poses[i];
      if (p.kind != cl::MoveKind::feed || poses[i - 1].kind != cl::MoveKind::feed ||
          poses[i + 1].kind != cl::MoveKind::feed) {
        continue;
      }
      const auto centre = [&](const cl::ClPose& q) -> Eigen::Vector3d {
        return Eigen::Vector3d(q.tip[0], q.tip[1], q.tip[2]) +
               r * Eigen::Vector3d(q.axis[0], q.axis[1], q.axis[2]);
      };
      const Eigen::Vector3d here = centre(p);
      if (std::abs(here.x()) > 6.5 || std::abs(here.y()) > 6.5) {
        continue;
      }
      const Eigen::Vector3d n = normal_under(here, r, c.a, c.b);
      const Eigen::Vector3d feed = centre(poses[i + 1]) - centre(poses[i - 1]);
      const Eigen::Vector3d ahead = (feed - feed.dot(n) * n).normalized();
      const Eigen::Vector3d left = n.cross(ahead);
      const Eigen::Vector3d axis(p.axis[0], p.axis[1], p.axis[2]);
      const double lead = std::atan2(axis.dot(ahead), axis.dot(n)) / lean_deg_rad;
      const double tilt = std::asin(std::clamp(axis.dot(left), -1.0, 1.0)) / lean_deg_rad;
      ++measured;
      as_asked += std::abs(lead - c.lead) <= 1.5 && std::abs(tilt - c.tilt) <= 1.5 ? 1 : 0;
    }
    INFO(as_asked << " of " << measured << " poses within 1.5 lean_deg_rad of the lean asked");
    REQUIRE(measured > 100);
    CHECK(as_asked >= measured * 95 / 100);
    geometry::VerifyOptions verify;
    verify.ball_radius = r;
    verify.scallop_target = h;
    verify.sample_spacing = 0.3;
    const auto report = geometry::verify_path(*surface, file, verify);
    REQUIRE(report);
    CHECK(report->max_scallop <= 1.05 * h);
    CHECK(report->max_gouge <= 1e-3);
    CHECK(report->links.deepest <= 1e-3);
    CHECK(report->rapids.samples == 0);
  }
}
