// The tool assembly's bodies, their distance to a point and their lowest point, against
// searches that do not share the formulas: a fine grid over each body's half-section.
#include "geometry/tool_assembly.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

using namespace subfeed;
using geometry::ToolAssembly;
using geometry::ToolBody;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

Eigen::Vector3d tilted_axis(double tilt_deg, double toward_deg) {
  return {std::sin(tilt_deg * deg) * std::cos(toward_deg * deg),
          std::sin(tilt_deg * deg) * std::sin(toward_deg * deg), std::cos(tilt_deg * deg)};
}

// The least distance from p to the body by a grid over the half-plane through the axis
// and p: the body's nearest point to p lies in it.
double grid_distance(const ToolBody& b, const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                     const Eigen::Vector3d& p, int steps) {
  const Eigen::Vector3d d = p - tip;
  const double along = d.dot(axis);
  const double across = (d - along * axis).norm();
  double best = 1e300;
  for (int i = 0; i <= steps; ++i) {
    const double h = b.from_mm + (b.to_mm - b.from_mm) * i / steps;
    const double radius =
        b.radius_from_mm + (b.radius_to_mm - b.radius_from_mm) * i / static_cast<double>(steps);
    for (int j = 0; j <= steps; ++j) {
      const double rho = radius * j / steps;
      best = std::min(best, std::hypot(along - h, across - rho));
    }
  }
  return best;
}

// The lowest z of the body by points round its two end circles.
double ring_lowest(const ToolBody& b, const Eigen::Vector3d& tip, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d u = axis.unitOrthogonal(), w = axis.cross(u);
  double lowest = 1e300;
  for (int k = 0; k < 7200; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / 7200;
    const Eigen::Vector3d round = std::cos(phi) * u + std::sin(phi) * w;
    lowest = std::min({lowest, (tip + b.from_mm * axis + b.radius_from_mm * round).z(),
                       (tip + b.to_mm * axis + b.radius_to_mm * round).z()});
  }
  return lowest;
}

} // namespace

TEST_CASE("a ball alone gets flutes 3D, a shank D and a stick-out 4D, named as defaults") {
  for (const double d : {1.0, 6.0, 20.0}) {
    const auto tool = ToolAssembly::ball_only(d / 2);
    CHECK(tool.defaulted);
    CHECK(tool.flute_length == 3 * d);
    CHECK(tool.shank_diameter == d);
    CHECK(tool.stickout == 4 * d);
    CHECK(tool.validate("--tool"));
    const auto bodies = tool.bodies();
    REQUIRE(bodies.size() == 2);
    CHECK(bodies[0].name == "flutes");
    CHECK(bodies[0].cuts);
    CHECK(bodies[0].from_mm == d / 2);
    CHECK(bodies[1].name == "shank");
    CHECK_FALSE(bodies[1].cuts);
    CHECK(tool.length() == 4 * d);
  }
}

TEST_CASE("holder stages stack from the stick-out up, bottom first, and bad sizes are named") {
  ToolAssembly tool{.ball_radius = 3,
                    .flute_length = 18,
                    .shank_diameter = 6,
                    .stickout = 40,
                    .holder = {{32, 32, 40}, {40, 20, 10}}};
  const auto bodies = tool.bodies();
  REQUIRE(bodies.size() == 4);
  CHECK(bodies[2].name == "holder 1");
  CHECK(bodies[2].from_mm == 40);
  CHECK(bodies[2].to_mm == 80);
  CHECK(bodies[3].name == "holder 2");
  CHECK(bodies[3].from_mm == 80);
  CHECK(bodies[3].radius_from_mm == 20);
  CHECK(bodies[3].radius_to_mm == 10);
  CHECK(tool.length() == 90);
  CHECK(tool.text() == "ball 6, flutes 18, shank 6, stick-out 40, holder 32:40 40:20:10");
  tool.stickout = 10;
  const auto short_stickout = tool.validate("--stickout");
  REQUIRE_FALSE(short_stickout);
  CHECK(short_stickout.error().describe() ==
        "--stickout: the stick-out (10 mm) must be at least the flute length (18 mm)");
  tool.stickout = 40;
  tool.flute_length = 2;
  CHECK_FALSE(tool.validate("--flute"));
}

TEST_CASE("a body's distance to a point is the section's distance, over cylinders and cones") {
  std::mt19937 random(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::vector<ToolBody> bodies{{"cylinder", 3, 18, 3, 3, true},
                                     {"cone out", 40, 60, 8, 16, false},
                                     {"cone in", 5, 25, 12, 2, false},
                                     {"disc", 10, 10.5, 20, 20, false}};
  for (const auto& body : bodies) {
    for (const double tilt : {0.0, 35.0, 90.0, 150.0}) {
      const Eigen::Vector3d tip(1.0, -2.0, 0.5);
      const Eigen::Vector3d axis = tilted_axis(tilt, 60.0);
      for (int i = 0; i < 40; ++i) {
        const Eigen::Vector3d p = tip +
                                  40.0 * Eigen::Vector3d(unit(random), unit(random), unit(random)) +
                                  (body.from_mm + 10.0) * axis;
        const double exact = geometry::body_distance(body, tip, axis, p);
        // The grid's points lie within half a cell of every point of the section.
        const double cell =
            std::max(body.to_mm - body.from_mm, std::max(body.radius_from_mm, body.radius_to_mm)) /
            400.0;
        const double grid = grid_distance(body, tip, axis, p, 400);
        INFO(body.name << " tilt " << tilt << " point " << p.transpose());
        CHECK(exact <= grid + 1e-9);
        CHECK(exact >= grid - cell);
      }
      // Inside reads 0: the middle of the body, on its axis.
      CHECK(geometry::body_distance(body, tip, axis,
                                    tip + 0.5 * (body.from_mm + body.to_mm) * axis) == 0.0);
    }
  }
}

TEST_CASE("a body's lowest point is the lower of its end circles' lowest, at every tilt") {
  const std::vector<ToolBody> bodies{{"shank", 18, 40, 3, 3, false},
                                     {"holder", 40, 80, 16, 16, false},
                                     {"cone", 80, 95, 20, 8, false}};
  for (const auto& body : bodies) {
    for (const double tilt : {0.0, 10.0, 45.0, 69.0, 90.0, 120.0, 180.0}) {
      for (const double toward : {0.0, 135.0, 270.0}) {
        const Eigen::Vector3d tip(5.0, 3.0, 2.0);
        const Eigen::Vector3d axis = tilted_axis(tilt, toward);
        INFO(body.name << " tilt " << tilt << " toward " << toward);
        CHECK(geometry::body_lowest_z(body, tip, axis) ==
              Approx(ring_lowest(body, tip, axis)).margin(1e-5));
      }
    }
  }
}
