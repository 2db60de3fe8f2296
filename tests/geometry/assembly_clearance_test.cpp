// The whole tool's clearance against parts with exact answers: a plane, where a body's
// distance is its lowest point's height, and a sphere, where it is the body's distance to
// the centre less the radius; over tilts, directions, heights and every body.
#include "geometry/assembly_clearance.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace subfeed;
using geometry::AssemblyClearance;
using geometry::Fixture;
using geometry::ToolAssembly;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

struct Mesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

// A square of side 2 half, at z = 0, in cells of `cell` mm.
Mesh plane(double half, double cell) {
  Mesh m;
  const int n = static_cast<int>(std::round(2 * half / cell));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.points.emplace_back(-half + i * cell, -half + j * cell, 0.0);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.triangles.push_back({a, a + 1, a + n + 2});
      m.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  }
  return m;
}

// A sphere of radius R about the origin, vertices on it: every triangle lies inside it,
// within R (1 - cos(pi / rings)) of it.
Mesh sphere(double radius, int rings) {
  Mesh m;
  const int around = 2 * rings;
  for (int j = 0; j <= rings; ++j) {
    const double theta = std::numbers::pi * j / rings;
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * std::numbers::pi * i / around;
      m.points.push_back(radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                  std::sin(theta) * std::sin(phi),
                                                  std::cos(theta)));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      m.triangles.push_back({a, b, b + around});
      m.triangles.push_back({a, b + around, a + around});
    }
  }
  return m;
}

Eigen::Vector3d tilted(double tilt_deg, double toward_deg) {
  return {std::sin(tilt_deg * deg) * std::cos(toward_deg * deg),
          std::sin(tilt_deg * deg) * std::sin(toward_deg * deg), std::cos(tilt_deg * deg)};
}

ToolAssembly issue_tool() {
  return {.ball_radius = 3,
          .flute_length = 18,
          .shank_diameter = 6,
          .stickout = 40,
          .holder = {{32, 32, 40}, {40, 24, 12}}};
}

} // namespace

TEST_CASE("over a plane each body's clearance is its lowest point's height, at every tilt") {
  const auto part = plane(150.0, 2.0);
  const geometry::TriangleTree tree(part.points, part.triangles);
  const auto tool = issue_tool();
  const Fixture fixture{std::nullopt, 0.0, 0.5};
  const AssemblyClearance clearance(tool, fixture, tree);
  const auto bodies = tool.bodies();
  for (const double tilt : {0.0, 15.0, 40.0, 65.0, 80.0}) {
    for (const double toward : {0.0, 110.0, 250.0}) {
      for (const double height : {0.2, 1.0, 4.0}) {
        const Eigen::Vector3d axis = tilted(tilt, toward);
        // The lowest body `height` above the plane.
        double lowest = 1e300;
        for (const auto& b : bodies) {
          lowest = std::min(lowest, geometry::body_lowest_z(b, Eigen::Vector3d::Zero(), axis));
        }
        const Eigen::Vector3d tip(3.0, -2.0, height - lowest);
        auto into = clearance.blank();
        const double cap = 3.0;
        const double slack = clearance.slack(tip, axis, cap, &into);
        double least = cap;
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          const double exact = geometry::body_lowest_z(bodies[i], tip, axis);
          INFO("tilt " << tilt << " toward " << toward << " height " << height << " "
                       << bodies[i].name);
          if (exact < 0.5) {
            // A broken rule ends the search: some distance under the rule is kept.
            CHECK(into[i + 1].to_part >= exact - 1e-9);
            CHECK(into[i + 1].to_part < 0.5);
          } else if (exact < 0.5 + cap - 0.05) {
            REQUIRE(std::isfinite(into[i + 1].to_part));
            CHECK(into[i + 1].to_part >= exact - 1e-9);
            CHECK(into[i + 1].to_part <=
                  exact + std::max(AssemblyClearance::resolution_mm, 0.25 * (exact - 0.5)) + 1e-9);
          }
          least = std::min(least, exact - 0.5);
        }
        // Slack never overstates, and breaks the rule exactly when a body is too near (by how
        // much is not searched for then).
        CHECK((slack < 0.0) == (least < 0.0));
        if (least >= 0.0) {
          CHECK(slack <= least + 1e-9);
        }
        CHECK(clearance.clear(tip, axis) == (least >= 0.0));
      }
    }
  }
}

TEST_CASE("beside a sphere each body's clearance is its distance to the centre less the radius") {
  const double radius = 20.0;
  const int rings = 300;
  const auto part = sphere(radius, rings);
  const double chord = radius * (1.0 - std::cos(std::numbers::pi / rings));
  const geometry::TriangleTree tree(part.points, part.triangles);
  for (const double r : {1.0, 3.0}) {
    ToolAssembly tool{.ball_radius = r,
                      .flute_length = 6 * r,
                      .shank_diameter = 2 * r,
                      .stickout = 12 * r,
                      .holder = {{10 * r, 10 * r, 10}}};
    const AssemblyClearance clearance(tool, {std::nullopt, 0.0, 0.5}, tree);
    const auto bodies = tool.bodies();
    for (const double lean : {0.0, 25.0, 50.0, 70.0}) {
      for (const double at : {10.0, 60.0, 100.0}) {
        // The ball on the sphere at `at` degrees from its pole, the axis leaning away from
        // the normal toward the pole.
        const Eigen::Vector3d n = tilted(at, 30.0);
        const Eigen::Vector3d toward_pole = (Eigen::Vector3d::UnitZ() - n.z() * n).normalized();
        const Eigen::Vector3d axis = std::cos(lean * deg) * n + std::sin(lean * deg) * toward_pole;
        const Eigen::Vector3d tip = (radius + r) * n - r * axis;
        auto into = clearance.blank();
        (void)clearance.slack(tip, axis, 5.0, &into);
        for (std::size_t i = 0; i < bodies.size(); ++i) {
          const double exact =
              geometry::body_distance(bodies[i], tip, axis, Eigen::Vector3d::Zero()) - radius;
          INFO("r " << r << " lean " << lean << " at " << at << " " << bodies[i].name << " exact "
                    << exact);
          if (exact <= 0.0) {
            CHECK(into[i + 1].to_part <= chord + 1e-9); // the body is in the sphere
          } else if (exact < 0.5) {
            CHECK(into[i + 1].to_part >= exact - 1e-9);
            CHECK(into[i + 1].to_part < 0.5);
          } else if (exact < 5.0) {
            CHECK(into[i + 1].to_part >= exact - 1e-9);
            CHECK(into[i + 1].to_part <=
                  exact + chord + std::max(AssemblyClearance::resolution_mm, 0.25 * (exact - 0.5)) +
                      1e-9);
          }
        }
      }
    }
  }
}

TEST_CASE("the floor: shank and holder stay above it, ball and flutes above the stock's bottom") {
  const auto part = plane(10.0, 2.0); // far off: only the floor counts here
  std::vector<Eigen::Vector3d> far;
  for (const auto& p : part.points) {
    far.push_back(p + Eigen::Vector3d(0, 0, 500));
  }
  const geometry::TriangleTree tree(far, part.triangles);
  const auto tool = issue_tool();
  const Fixture fixture{2.0, 1.5, 0.5}; // floor at z 2, stock down to 0.5
  const Fixture deep_stock{2.0, 20.0, 0.5};
  const AssemblyClearance tilted_tool(tool, deep_stock, tree);
  const AssemblyClearance clearance(tool, fixture, tree);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // Vertical: the ball's bottom is the tip.
  CHECK(clearance.clear({0, 0, 0.5}, up));
  const auto under_stock = clearance.violation({0, 0, 0.4}, up);
  REQUIRE(under_stock);
  CHECK(under_stock->body == "ball");
  CHECK(under_stock->floor);
  CHECK(under_stock->distance == Approx(0.1));
  // Tilted 69 degrees, as on the dome's foot: the holder's rim reaches lowest.
  const Eigen::Vector3d lean = tilted(69.0, 0.0);
  const double holder_low =
      geometry::body_lowest_z(tool.bodies()[2], Eigen::Vector3d::Zero(), lean);
  const auto holder = tilted_tool.violation({0, 0, 2.0 - holder_low - 0.3}, lean);
  REQUIRE(holder);
  CHECK(holder->body == "holder 1");
  CHECK(holder->distance == Approx(0.3));
  CHECK(tilted_tool.clear({0, 0, 2.0 - holder_low + 0.01}, lean));
  auto into = tilted_tool.blank();
  CHECK(tilted_tool.floor_slack({0, 0, 2.0 - holder_low + 0.01}, lean, &into) ==
        Approx(0.01 + AssemblyClearance::floor_tolerance_mm));
  CHECK(into[3].to_floor == Approx(0.01));
}
