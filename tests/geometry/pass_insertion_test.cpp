// Where passes go between the planes: the spacing measure on fields with known level-line
// spacing (uniform, and a chevron whose lines lie farther apart at the kink than any one
// triangle shows), the depth of each fractional level, and the growth of the region.

#include "geometry/pass_insertion.hpp"

#include "support/uniform_need.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace subfeed::geometry;

namespace {

struct Grid {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

// n x n vertices, spacing h, on z = 0.
Grid flat_grid(int n, double h) {
  Grid g;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      g.points.emplace_back(i * h, j * h, 0.0);
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i;
      g.triangles.push_back({v, v + 1, v + n + 1});
      g.triangles.push_back({v, v + n + 1, v + n});
    }
  }
  return g;
}

PassIntervals needing(std::size_t vertices, double spacing) {
  return subfeed::testing::uniform_need(vertices, spacing);
}

} // namespace

TEST_CASE("level_depth: whole planes 0, halves 1, quarters 2, ...") {
  const long per_plane = 1L << max_insertion_depth;
  CHECK(level_depth(0) == 0);
  CHECK(level_depth(3 * per_plane) == 0);
  CHECK(level_depth(per_plane / 2) == 1);
  CHECK(level_depth(per_plane / 4) == 2);
  CHECK(level_depth(3 * per_plane / 4) == 2);
  CHECK(level_depth(1) == max_insertion_depth);
}

TEST_CASE("spacing ratio of a uniform field is exact, and the predicted length is the co-area "
          "integral") {
  const auto g = flat_grid(21, 0.1); // 2 x 2 mm
  std::vector<double> phi;
  for (const auto& p : g.points) {
    phi.push_back(0.5 * p.y()); // levels 0.1 apart in phi: lines 0.2 mm apart
  }
  const auto ratios = spacing_ratios(g.points, g.triangles, phi, 0.1, needing(phi.size(), 0.25));
  for (const double r : ratios.ratio) {
    CHECK(r == Approx(0.2 / 0.25).epsilon(1e-12));
  }
  const auto none =
      pass_insertion(g.points, g.triangles, phi, 0.1, needing(phi.size(), 0.25), 0.1, 0.0);
  CHECK(none.max_depth == 0);
  CHECK(none.predicted_length == Approx(2.0 * 2.0 / 0.2).epsilon(1e-12)); // 10 lines of 2 mm
  // Need 0.07: lines 0.2 apart need two halvings (0.05 <= 0.07 < 0.1).
  const auto two =
      pass_insertion(g.points, g.triangles, phi, 0.1, needing(phi.size(), 0.07), 0.1, 0.0);
  CHECK(two.max_depth == 2);
  CHECK(two.predicted_length == Approx(4 * 20.0).epsilon(1e-12));
}

TEST_CASE("a chevron's kink is seen: lines farther apart there than either side's gradient") {
  const auto g = flat_grid(21, 0.1);
  std::vector<double> phi;
  for (const auto& p : g.points) {
    phi.push_back(p.y() - std::abs(p.x() - 1.0)); // lines kink along x = 1
  }
  // Each triangle's own gradient has length sqrt(2): lines 1/sqrt(2) apart per unit step.
  // At the kink the lines are a whole unit apart vertically, and the point of the gap
  // farthest from both (on the kink, below the upper line's corner) is
  // 1 / (1 + sqrt(2)) from each: the lines are as far apart as straight lines
  // 2 / (1 + sqrt(2)) apart, not a whole unit.
  const auto ratios = spacing_ratios(g.points, g.triangles, phi, 1.0, needing(phi.size(), 0.8));
  double at_kink = 0.0, away = 0.0;
  for (std::size_t t = 0; t < g.triangles.size(); ++t) {
    bool touches = false;
    for (const int v : g.triangles[t]) {
      touches = touches || std::abs(g.points[static_cast<std::size_t>(v)].x() - 1.0) < 1e-9;
    }
    (touches ? at_kink : away) = std::max(touches ? at_kink : away, ratios.ratio[t]);
  }
  CHECK(away == Approx(1.0 / std::sqrt(2.0) / 0.8).epsilon(1e-9));
  CHECK(at_kink == Approx(2.0 / (1.0 + std::sqrt(2.0)) / 0.8).epsilon(1e-9));
}

TEST_CASE("the gap a chevron leaves is what the distances to its lines say") {
  // Lines y = c + a |x - 1|, one unit apart in c: the widest gap between two of them, found
  // by brute force over points between, is half the spacing that straight lines with the
  // same gap would have. The kink's ratio must say that spacing, not more and not less.
  const double a = 0.5;
  const auto to_line = [&](double px, double py, double c) {
    double best = std::numeric_limits<double>::infinity();
    for (const double side : {1.0, -1.0}) {
      const Eigen::Vector2d dir = Eigen::Vector2d(side, a).normalized();
      const Eigen::Vector2d rel(px - 1.0, py - c);
      const double t = std::max(0.0, rel.dot(dir));
      best = std::min(best, (rel - t * dir).norm());
    }
    return best;
  };
  double gap = 0.0;
  for (int i = 0; i <= 2000; ++i) {
    for (int j = -200; j <= 200; ++j) {
      const double px = 1.0 + j / 400.0, py = i / 2000.0;
      gap = std::max(gap, std::min(to_line(px, py, 0.0), to_line(px, py, 1.0)));
    }
  }
  const auto g = flat_grid(21, 0.1);
  std::vector<double> phi;
  for (const auto& p : g.points) {
    phi.push_back(p.y() - a * std::abs(p.x() - 1.0));
  }
  const auto ratios = spacing_ratios(g.points, g.triangles, phi, 1.0, needing(phi.size(), 0.8));
  const double widest = std::ranges::max(ratios.ratio);
  CHECK(widest == Approx(2.0 * gap / 0.8).epsilon(1e-3));
}

TEST_CASE("inserted passes reach a margin past where they are needed") {
  const auto g = flat_grid(41, 0.1); // 4 x 4 mm
  std::vector<double> phi;
  for (const auto& p : g.points) {
    phi.push_back(p.y());
  }
  auto need = needing(phi.size(), 2.0);
  for (std::size_t v = 0; v < phi.size(); ++v) {
    if (g.points[v].x() < 1.0) {
      need.cl_spacing[v] = 0.6; // lines 1 mm apart are too far apart only for x < 1
    }
  }
  const auto insertion = pass_insertion(g.points, g.triangles, phi, 1.0, need, 0.5, 0.0);
  CHECK(insertion.max_depth == 1);
  for (std::size_t t = 0; t < g.triangles.size(); ++t) {
    double x = 0.0;
    for (const int v : g.triangles[t]) {
      x += g.points[static_cast<std::size_t>(v)].x() / 3.0;
    }
    if (x < 1.0 || (x > 1.2 && x < 1.45)) {
      CHECK(insertion.depth[t] == 1); // needed, or within the 0.5 mm margin
    }
    if (x > 1.8) {
      CHECK(insertion.depth[t] == 0);
    }
  }
}
