// Rings about the highest point: the marched front's arrival times against exact distances
// on a flat grid (a point source, uniform and doubled slowness, two sources), the sources
// per piece, the ring levels, and rings whose measured spacing is the need away from their
// centre.

#include "geometry/concentric_field.hpp"
#include "geometry/front_arrival.hpp"
#include "geometry/pass_insertion.hpp"

#include "support/uniform_need.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

using namespace subfeed::geometry;

namespace {

struct Grid {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

// n x n vertices, spacing h, from (x0, 0) on the plane z = height, appended to g.
void add_grid(Grid& g, int n, double h, double x0 = 0.0, double height = 0.0) {
  const int base = static_cast<int>(g.points.size());
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      g.points.emplace_back(x0 + i * h, j * h, height);
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int v = base + j * n + i;
      // Alternate the diagonal so the mesh has no preferred direction.
      if ((i + j) % 2 == 0) {
        g.triangles.push_back({v, v + 1, v + n + 1});
        g.triangles.push_back({v, v + n + 1, v + n});
      } else {
        g.triangles.push_back({v, v + 1, v + n});
        g.triangles.push_back({v + 1, v + n + 1, v + n});
      }
    }
  }
}

PassIntervals needing(std::size_t vertices, double spacing) {
  return subfeed::testing::uniform_need(vertices, spacing);
}

// Largest relative error of t against slowness * distance to the nearest source, over the
// vertices farther than `beyond` from every source.
double worst_error(const Grid& g, const std::vector<double>& t, const std::vector<int>& sources,
                   double slowness, double beyond) {
  double worst = 0.0;
  for (std::size_t v = 0; v < g.points.size(); ++v) {
    double d = 1e300;
    for (const int s : sources) {
      d = std::min(d, (g.points[v] - g.points[static_cast<std::size_t>(s)]).norm());
    }
    if (d > beyond) {
      worst = std::max(worst, std::abs(t[v] / (slowness * d) - 1.0));
    }
  }
  return worst;
}

} // namespace

TEST_CASE("front arrival on a flat grid: distance times slowness, from the nearest source") {
  Grid g;
  add_grid(g, 41, 0.25); // 10 x 10 mm
  const int centre = 20 * 41 + 20;
  SECTION("one source, uniform slowness") {
    const auto t =
        front_arrival(g.points, g.triangles, std::vector<double>(g.points.size(), 1.0), {centre});
    CHECK(t[static_cast<std::size_t>(centre)] == 0.0);
    CHECK(worst_error(g, t, {centre}, 1.0, 2.0) < 0.03); // first order: 2.5 % at 8 cells
  }
  SECTION("doubled slowness doubles every time") {
    const auto one =
        front_arrival(g.points, g.triangles, std::vector<double>(g.points.size(), 1.0), {centre});
    const auto two =
        front_arrival(g.points, g.triangles, std::vector<double>(g.points.size(), 2.0), {centre});
    for (std::size_t v = 0; v < one.size(); ++v) {
      CHECK(two[v] == Approx(2.0 * one[v]).margin(1e-12));
    }
  }
  SECTION("two sources: the nearer one") {
    const int left = 20 * 41 + 4, right = 20 * 41 + 36;
    const auto t = front_arrival(g.points, g.triangles, std::vector<double>(g.points.size(), 1.0),
                                 {left, right});
    CHECK(worst_error(g, t, {left, right}, 1.0, 2.0) < 0.03);
  }
  SECTION("a piece without a source is never reached") {
    add_grid(g, 5, 0.25, 20.0);
    const auto t =
        front_arrival(g.points, g.triangles, std::vector<double>(g.points.size(), 1.0), {centre});
    CHECK(std::isinf(t.back()));
    CHECK(std::isfinite(t[0]));
  }
}

TEST_CASE("highest_points: the highest reachable vertex of each piece") {
  Grid g;
  add_grid(g, 5, 1.0);
  add_grid(g, 5, 1.0, 10.0);
  g.points[12].z() = 3.0;      // the first piece's middle
  g.points[25 + 6].z() = 2.0;  // the second piece, reachable
  g.points[25 + 18].z() = 5.0; // higher, but in a hollow the ball cannot reach
  std::vector<char> reachable(g.points.size(), 1);
  reachable[25 + 18] = 0;
  auto top = highest_points(g.points, g.triangles, reachable);
  std::ranges::sort(top);
  CHECK(top == std::vector<int>{12, 25 + 6});
}

TEST_CASE("ring levels start half a step above the centre, then one step apart") {
  const auto levels = ring_levels({0.0, 0.3, 2.0, 1.1}, 0.5);
  CHECK(levels.first == Approx(0.25));
  CHECK(levels.step == 0.5);
  CHECK(levels.planes == 4); // 0.25, 0.75, 1.25, 1.75
  CHECK(ring_levels({}, 0.5).planes == 0);
}

TEST_CASE("rings on a flat grid lie the need apart: nothing inserted, priced as circles") {
  Grid g;
  add_grid(g, 81, 0.125); // 10 x 10 mm, highest point in the middle
  g.points[40 * 81 + 40].z() = 1e-3;
  const double need = 0.4;
  const auto intervals = needing(g.points.size(), need);
  ConcentricSettings settings;
  settings.reference = 0.2; // any scale: the levels are one reference apart
  settings.spacing_allowance = 0.02;
  settings.insertion_margin = need;
  const auto d = concentric_deformation(g.points, g.points, g.triangles, intervals, {}, settings);
  REQUIRE(d.ring_centres == std::vector<int>{40 * 81 + 40});
  // Arrival in mm of deformed coordinate: distance * reference / need.
  CHECK(worst_error(g, d.deformed, d.ring_centres, settings.reference / need, 2.0) < 0.02);
  CHECK(d.planes.first == Approx(0.1).margin(1e-12));
  CHECK(d.insertion.max_depth == 0);
  CHECK(d.worst_ratio < 1.02);
  // Co-area: the level lines' length is the area over the spacing, 100 / 0.4 mm.
  CHECK(d.insertion.predicted_length == Approx(100.0 / need).epsilon(0.02));
}
