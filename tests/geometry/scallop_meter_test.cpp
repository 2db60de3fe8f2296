#include "geometry/scallop_meter.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using subfeed::geometry::Capsule;
using subfeed::geometry::measure_scallop;

namespace {

constexpr double r = 5.0;

// Two passes along Y whose contact points on a cylinder of signed radius rho (axis along Y)
// are 1.2 mm apart; returns the scallop at the surface point midway between them.
double scallop_between_passes(double rho) {
  const double phi = std::asin(0.6 / std::abs(rho));
  std::vector<Capsule> capsules;
  for (const double side : {-1.0, 1.0}) {
    const double theta = side * phi;
    // Surface point and its normal toward the tool; the ball centre sits r along the normal.
    const Eigen::Vector3d point =
        rho > 0 ? Eigen::Vector3d(rho * std::sin(theta), 0, rho * std::cos(theta))
                : Eigen::Vector3d(-rho * std::sin(theta), 0, rho * std::cos(theta));
    const Eigen::Vector3d normal = rho > 0 ? Eigen::Vector3d(std::sin(theta), 0, std::cos(theta))
                                           : Eigen::Vector3d(-std::sin(theta), 0, std::cos(theta));
    const Eigen::Vector3d centre = point + r * normal;
    capsules.push_back({centre - Eigen::Vector3d(0, 10, 0), centre + Eigen::Vector3d(0, 10, 0), r});
  }
  const Eigen::Vector3d p(0, 0, rho);
  return measure_scallop(p, Eigen::Vector3d::UnitZ(), capsules, 1.0).height;
}

} // namespace

TEST_CASE("the scallop meter reproduces docs/METHOD.md's known answers") {
  std::vector<Capsule> flat;
  for (const double x : {-0.6, 0.6}) {
    flat.push_back({{x, -10, r}, {x, 10, r}, r});
  }
  const auto sample = measure_scallop({0, 0, 0}, Eigen::Vector3d::UnitZ(), flat, 1.0);
  CHECK(sample.height == Approx(3.613054e-2).epsilon(1e-6));
  CHECK(sample.gouge_depth == 0.0);
  CHECK(scallop_between_passes(20.0) == Approx(4.531748e-2).epsilon(1e-6));
  CHECK(scallop_between_passes(-20.0) == Approx(2.704269e-2).epsilon(1e-6));
}

TEST_CASE("the meter agrees with the flat closed form to high precision") {
  for (const double half : {0.05, 0.3, 1.0, 2.5}) {
    const std::vector<Capsule> passes{{{-half, -10, r}, {-half, 10, r}, r},
                                      {{half, -10, r}, {half, 10, r}, r}};
    const double exact = r - std::sqrt(r * r - half * half);
    CHECK(std::abs(measure_scallop({0, 0, 0}, Eigen::Vector3d::UnitZ(), passes, 1.0).height -
                   exact) < 1e-10);
  }
}

TEST_CASE("at a contact point nothing is left, a ball below the surface is a gouge") {
  const std::vector<Capsule> pass{{{0, -10, r}, {0, 10, r}, r}};
  const auto contact = measure_scallop({0, 0, 0}, Eigen::Vector3d::UnitZ(), pass, 1.0);
  CHECK(contact.height == Approx(0.0).margin(1e-12));
  CHECK(contact.gouge_depth < 1e-12);
  const std::vector<Capsule> deep{{{0, -10, r - 0.05}, {0, 10, r - 0.05}, r}};
  const auto gouge = measure_scallop({0, 0, 0}, Eigen::Vector3d::UnitZ(), deep, 1.0);
  CHECK(gouge.gouge_depth == Approx(0.05));
  CHECK(gouge.height == 0.0);
}

TEST_CASE("a point no pass reaches is reported uncut") {
  const std::vector<Capsule> far{{{20, -10, r}, {20, 10, r}, r}};
  CHECK(std::isinf(measure_scallop({0, 0, 0}, Eigen::Vector3d::UnitZ(), far, 1.0).height));
  // The ends of a capsule are spherical: just past the end of a pass the scallop grows.
  const std::vector<Capsule> short_pass{{{0, -10, r}, {0, 0, r}, r}};
  const auto beyond = measure_scallop({0, 1, 0}, Eigen::Vector3d::UnitZ(), short_pass, 1.0);
  CHECK(beyond.height == Approx(r - std::sqrt(r * r - 1.0)).epsilon(1e-9));
}
