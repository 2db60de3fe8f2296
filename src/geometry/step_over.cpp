#include "geometry/step_over.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::geometry {

double flat_step(double r, double h) {
  return 2.0 * std::sqrt(h * (2.0 * r - h));
}

double flat_scallop(double r, double w) {
  const double q = w * w / 4.0;
  return q / (r + std::sqrt(r * r - q)); // r - sqrt(r^2 - q) without the cancellation
}

double contact_step(double r, double h, double rho) {
  // In a hollow barely wider than the ball x passes 1: neighbouring contacts more than a
  // quarter turn apart round the centre of curvature still leave less than h, so the step
  // is the whole width of the hollow's contact circle (x = 1, alpha = 90 deg).
  const double x = std::min(1.0, h * (2.0 * r - h) / (2.0 * (rho + r) * (rho + h)));
  return 2.0 * std::abs(rho) * std::sqrt(x * (2.0 - x));
}

double contact_scallop(double r, double w, double rho) {
  // sin(alpha) = w / (2|rho|), x = 1 - cos(alpha); then h solves
  // h^2 - B h + C = 0 with B = 2r - 2x(rho + r), C = 2x rho (rho + r): the smaller root.
  const double s = w / (2.0 * std::abs(rho));
  const double x = s * s / (1.0 + std::sqrt(1.0 - s * s));
  const double b = 2.0 * r - 2.0 * x * (rho + r);
  const double c = 2.0 * x * rho * (rho + r);
  return 2.0 * c / (b + std::sqrt(b * b - 4.0 * c));
}

double cl_step(double r, double h, double rho) {
  return contact_step(r, h, rho) * (rho + r) / rho;
}

double plane_interval(double cl_spacing, double s_dot_n) {
  return cl_spacing * std::sqrt(1.0 - s_dot_n * s_dot_n);
}

} // namespace subfeed::geometry
