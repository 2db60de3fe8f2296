// The nearest point of a triangle against a brute-force search over a fine barycentric grid.

#include "geometry/closest_point.hpp"

#include <catch2/catch.hpp>
#include <random>

using subfeed::geometry::closest_on_triangle;

TEST_CASE("closest point on a triangle agrees with a dense search in every Voronoi region") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  const auto random_point = [&] { return Eigen::Vector3d(coord(rng), coord(rng), coord(rng)); };
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = random_point(), b = random_point(), c = random_point();
    const Eigen::Vector3d p = random_point() * 2.0;
    const Eigen::Vector3d q = closest_on_triangle(p, a, b, c);
    double best = 1e300;
    constexpr int n = 200;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        best = std::min(best, (a + u * (b - a) + v * (c - a) - p).norm());
      }
    }
    // The dense grid can only be as far or farther, by at most its own spacing.
    const double spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    CHECK((q - p).norm() <= best + 1e-12);
    CHECK((q - p).norm() >= best - spacing);
  }
}

TEST_CASE("closest point: vertex, edge and face regions exactly") {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK((closest_on_triangle({-1, -1, 3}, a, b, c) - a).norm() < 1e-15);
  CHECK((closest_on_triangle({2, -0.5, 1}, a, b, c) - b).norm() < 1e-15);
  CHECK((closest_on_triangle({0.5, -3, 0}, a, b, c) - Eigen::Vector3d(0.5, 0, 0)).norm() < 1e-15);
  CHECK((closest_on_triangle({1, 1, 0}, a, b, c) - Eigen::Vector3d(0.5, 0.5, 0)).norm() < 1e-15);
  CHECK((closest_on_triangle({0.2, 0.3, -5}, a, b, c) - Eigen::Vector3d(0.2, 0.3, 0)).norm() <
        1e-15);
}

TEST_CASE("closest point on a segment: the ends, the inside, and a zero-length segment") {
  using subfeed::geometry::closest_on_segment;
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0);
  CHECK((closest_on_segment({-1, 1, 0}, a, b) - a).norm() < 1e-15);
  CHECK((closest_on_segment({3, -1, 2}, a, b) - b).norm() < 1e-15);
  CHECK((closest_on_segment({0.5, 4, -3}, a, b) - Eigen::Vector3d(0.5, 0, 0)).norm() < 1e-15);
  CHECK((closest_on_segment({5, 5, 5}, a, a) - a).norm() < 1e-15);
}
