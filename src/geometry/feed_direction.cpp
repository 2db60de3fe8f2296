#include "geometry/feed_direction.hpp"

#include "geometry/pass_intervals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace subfeed::geometry {

Eigen::Vector3d slicing_normal_for(double direction_deg) {
  const double a = direction_deg * std::numbers::pi / 180.0;
  return {-std::sin(a), std::cos(a), 0.0}; // +Z x the feed (cos a, sin a, 0)
}

namespace {

Expected<Deformation> deform_along(const SurfaceMesh& mesh,
                                   const std::vector<Eigen::Vector3d>& cl_points,
                                   const std::vector<Eigen::Vector3d>& path_points,
                                   const DirectionPricing& p, double direction_deg, int solves,
                                   const SolveProgress& on_solve) {
  const Eigen::Vector3d s = slicing_normal_for(direction_deg);
  const auto intervals = pass_intervals(mesh, p.ball_radius, p.scallop, s);
  const double margin = p.insertion_margin.value_or(std::ranges::max(intervals.cl_spacing));
  return deform_cl_mesh(cl_points, path_points, mesh.triangles, s, intervals, solves, margin,
                        p.spacing_allowance, on_solve);
}

} // namespace

Expected<DirectionChoice> choose_feed_direction(const SurfaceMesh& mesh,
                                                const std::vector<Eigen::Vector3d>& cl_points,
                                                const std::vector<Eigen::Vector3d>& path_points,
                                                const DirectionPricing& pricing,
                                                const SolveProgress& on_solve) {
  DirectionChoice choice;
  const auto tried = [&](double deg) -> Expected<void> {
    SUBFEED_TRY_ASSIGN(const auto d, deform_along(mesh, cl_points, path_points, pricing, deg,
                                                  pricing.solves, on_solve));
    choice.prices.push_back({deg, d.insertion.predicted_length});
    return {};
  };
  for (const double deg : {0.0, 45.0, 90.0, 135.0}) {
    SUBFEED_TRY(tried(deg));
  }
  const auto cheapest = [&] {
    return std::ranges::min(choice.prices, {}, &DirectionPrice::predicted_length).direction_deg;
  };
  const double coarse = cheapest();
  // Passes repeat every 180 degrees: 0 and 157.5 are neighbours.
  for (const double deg : {coarse - 22.5, coarse + 22.5}) {
    SUBFEED_TRY(tried(std::fmod(deg + 180.0, 180.0)));
  }
  const double best = cheapest();
  // Along a machine axis unless another direction is clearly cheaper: the prediction leaves
  // out boundary passes and how far inserted passes run, about 2 % of the length.
  const auto price_of = [&](double deg) {
    return std::ranges::find(choice.prices, deg, &DirectionPrice::direction_deg)->predicted_length;
  };
  const double axis = price_of(0.0) <= price_of(90.0) ? 0.0 : 90.0;
  const auto clearly_cheaper = [&](double other, double than_axis) {
    return than_axis > (1.0 + pricing.axis_preference) * other;
  };
  if (!clearly_cheaper(price_of(best), price_of(axis))) {
    choice.direction_deg = axis;
    return choice;
  }
  SUBFEED_TRY_ASSIGN(auto off_axis, deform_along(mesh, cl_points, path_points, pricing, best,
                                                 pricing.full_solves, on_solve));
  SUBFEED_TRY_ASSIGN(auto on_axis, deform_along(mesh, cl_points, path_points, pricing, axis,
                                                pricing.full_solves, on_solve));
  const double off_length = off_axis.insertion.predicted_length;
  const double on_length = on_axis.insertion.predicted_length;
  choice.prices.push_back({best, off_length, true});
  choice.prices.push_back({axis, on_length, true});
  const bool off_wins = clearly_cheaper(off_length, on_length);
  choice.direction_deg = off_wins ? best : axis;
  choice.deformation = std::move(off_wins ? off_axis : on_axis);
  choice.solved_in_full = true;
  return choice;
}

} // namespace subfeed::geometry
