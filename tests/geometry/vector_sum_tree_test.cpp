// The tree's sums against adding every point within the ball one by one: random clouds,
// a surface-like sheet (the planner's use), radii from below the spacing to beyond the cloud.

#include "geometry/vector_sum_tree.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace subfeed;

TEST_CASE("sums within a ball match the sum point by point", "[unit]") {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0), unit(-1.0, 1.0);
  for (const bool sheet : {false, true}) {
    INFO((sheet ? "a wavy sheet" : "a cloud"));
    std::vector<Eigen::Vector3d> points, vectors;
    for (int i = 0; i < 3000; ++i) {
      const double x = coordinate(random), y = coordinate(random);
      points.emplace_back(x, y, sheet ? std::sin(0.3 * x) * std::cos(0.2 * y) : coordinate(random));
      vectors.emplace_back(unit(random), unit(random), unit(random));
    }
    const geometry::VectorSumTree tree(points, vectors);
    for (const double radius : {0.05, 0.7, 3.0, 9.0, 40.0}) {
      for (int k = 0; k < 30; ++k) {
        const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random) * 0.2);
        Eigen::Vector3d want = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < points.size(); ++i) {
          if ((points[i] - p).squaredNorm() <= radius * radius) {
            want += vectors[i];
          }
        }
        INFO("radius " << radius << " at " << p.transpose());
        CHECK((tree.sum_within(p, radius) - want).norm() < 1e-9);
      }
    }
  }
  CHECK(geometry::VectorSumTree({}, {}).sum_within(Eigen::Vector3d::Zero(), 1.0).norm() == 0.0);
}
