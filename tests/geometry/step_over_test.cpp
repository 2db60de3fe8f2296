#include "geometry/step_over.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace subfeed::geometry;

namespace {

// The exact construction by the law of cosines: ball centres at distance rho + r from the
// centre of curvature, the cusp at rho + h; the contact points lie at the angle alpha
// between a ball centre and the cusp. It cancels as cos(alpha) nears 1, so it is evaluated
// in extended precision to serve as the reference.
double law_of_cosines_step(double r, double h, double rho) {
  const long double centre = static_cast<long double>(rho) + r;
  const long double cusp = static_cast<long double>(rho) + h;
  const long double c =
      (centre * centre + cusp * cusp - static_cast<long double>(r) * r) / (2.0L * centre * cusp);
  return static_cast<double>(2.0L * std::abs(static_cast<long double>(rho)) *
                             std::sqrt((1.0L - c) * (1.0L + c)));
}

} // namespace

TEST_CASE("flat step-over and scallop are inverse closed forms") {
  CHECK(flat_scallop(5.0, 1.2) == Approx(3.613054e-2).epsilon(1e-6));
  for (const double r : {0.5, 3.0, 5.0, 12.5}) {
    for (const double h : {1e-4, 1e-3, 0.01, 0.1}) {
      const double w = flat_step(r, h);
      CHECK(w == Approx(2.0 * std::sqrt(2.0 * r * h - h * h)).epsilon(1e-14));
      CHECK(std::abs(flat_scallop(r, w) - h) < 1e-12 * std::max(1.0, h));
    }
  }
}

TEST_CASE("curved step-over matches the law of cosines and docs/METHOD.md's known answers") {
  constexpr double r = 5.0;
  // Scallops measured for a 1.2 mm chord (docs/METHOD.md §5).
  CHECK(contact_step(r, 4.531748e-2, 20.0) == Approx(1.2).epsilon(1e-6));
  CHECK(contact_step(r, 2.704269e-2, -20.0) == Approx(1.2).epsilon(1e-6));
  CHECK(contact_scallop(r, 1.2, 20.0) == Approx(4.531748e-2).epsilon(1e-6));
  CHECK(contact_scallop(r, 1.2, -20.0) == Approx(2.704269e-2).epsilon(1e-6));
  for (const double rho : {-200.0, -40.0, -7.5, 6.0, 20.0, 80.0, 1000.0}) {
    for (const double h : {1e-3, 0.01, 0.05}) {
      const double w = contact_step(r, h, rho);
      CHECK(std::abs(w - law_of_cosines_step(r, h, rho)) < 1e-12);
      CHECK(std::abs(contact_scallop(r, w, rho) - h) < 1e-12);
    }
  }
}

TEST_CASE("the curved form stays exact where the textbook form cancels") {
  // For huge |rho| the step tends to flat * rho / sqrt((rho + r)(rho + h)), exact to
  // O(h r / rho^2). docs/METHOD.md: the textbook form is off by 3e-4 mm at 1e6 and gives 0 at 1e9.
  constexpr double r = 5.0, h = 0.01;
  for (const double rho : {1e6, 1e9, 1e12, -1e9}) {
    const double asymptote = flat_step(r, h) * std::abs(rho) / std::sqrt((rho + r) * (rho + h));
    CHECK(contact_step(r, h, rho) == Approx(asymptote).epsilon(1e-12));
  }
  // First-order check from docs/METHOD.md: w ~ sqrt(8 r h rho / (rho + r)).
  CHECK(contact_step(r, 1e-4, 20.0) ==
        Approx(std::sqrt(8.0 * r * 1e-4 * 20.0 / 25.0)).epsilon(1e-4));
}

TEST_CASE("a hollow barely wider than the ball takes a step across its whole contact circle") {
  // x = h(2r - h) / (2(rho + r)(rho + h)) passes 1 (more than a quarter turn between
  // contacts): sqrt(x(2 - x)) was NaN there, and a NaN interval poisons the deformation.
  constexpr double r = 5.0, h = 0.01, rho = -5.004;
  const double w = contact_step(r, h, rho);
  REQUIRE(std::isfinite(w));
  CHECK(w == Approx(2.0 * std::abs(rho)).epsilon(1e-12));
  CHECK(contact_scallop(r, w, rho) <= h);
  CHECK(std::isfinite(cl_step(r, h, rho)));
  CHECK(cl_step(r, h, rho) > 0.0);
}

TEST_CASE("ball centres spread on convex and crowd on concave surfaces") {
  constexpr double r = 5.0, h = 0.02;
  CHECK(cl_step(r, h, 20.0) == Approx(contact_step(r, h, 20.0) * 25.0 / 20.0));
  CHECK(cl_step(r, h, -20.0) == Approx(contact_step(r, h, -20.0) * 15.0 / 20.0));
  CHECK(contact_step(r, h, -20.0) / cl_step(r, h, -20.0) ==
        Approx(20.0 / 15.0)); // x1.33 at rho = -20
}

TEST_CASE("slicing planes close up where the CL surface slopes across them") {
  CHECK(plane_interval(1.0, 0.0) == 1.0);
  CHECK(plane_interval(1.0, std::sin(60.0 * M_PI / 180.0)) == Approx(0.5));
  CHECK(plane_interval(2.0, 1.0) == 0.0);
}
