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
  const auto intervals = pass_intervals(mesh, p.ball_radius, p.scallop, s, p.in_reach);
  const double margin = p.insertion_margin.value_or(std::ranges::max(intervals.cl_spacing));
  if (p.coarse != nullptr) {
    // The cheapest of a candidate's few coarse solves, measured on the fine mesh once;
    // a full solve takes the fine rounds too.
    return p.coarse->solve(mesh, cl_points, path_points, s, intervals,
                           {.coarse_rounds = solves,
                            .fine_rounds = solves < p.full_solves ? 1 : p.fine_rounds,
                            .insertion_margin = margin,
                            .allowance = p.spacing_allowance,
                            .on_solve = on_solve});
  }
  const auto need = [&](const std::vector<Eigen::Vector3d>& across) {
    return cl_spacing_across(mesh, p.ball_radius, p.scallop, across, intervals.cl_spacing);
  };
  return deform_cl_mesh(cl_points, path_points, mesh.triangles, s, intervals, solves, margin,
                        p.spacing_allowance, on_solve, need);
}

// Whether `other` is cheaper than the axis's `axis_length` by more than the preference.
bool clearly_cheaper(const DirectionPricing& p, double other, double axis_length) {
  return axis_length > (1.0 + p.axis_preference) * other;
}

double price_of(const std::vector<DirectionPrice>& prices, double deg) {
  return std::ranges::find(prices, deg, &DirectionPrice::direction_deg)->predicted_length;
}

// Solves `off_axis` and `choice`'s axis in full and keeps the cheaper, with the preference.
Expected<void> confirm_in_full(const SurfaceMesh& mesh,
                               const std::vector<Eigen::Vector3d>& cl_points,
                               const std::vector<Eigen::Vector3d>& path_points,
                               const DirectionPricing& pricing, double off_axis,
                               const SolveProgress& on_solve, DirectionChoice& choice) {
  const double axis = choice.direction_deg;
  SUBFEED_TRY_ASSIGN(auto off, deform_along(mesh, cl_points, path_points, pricing, off_axis,
                                            pricing.full_solves, on_solve));
  SUBFEED_TRY_ASSIGN(auto on, deform_along(mesh, cl_points, path_points, pricing, axis,
                                           pricing.full_solves, on_solve));
  choice.prices.push_back({off_axis, off.insertion.predicted_length, true});
  choice.prices.push_back({axis, on.insertion.predicted_length, true});
  const bool off_wins =
      clearly_cheaper(pricing, off.insertion.predicted_length, on.insertion.predicted_length);
  choice.direction_deg = off_wins ? off_axis : axis;
  choice.deformation = std::move(off_wins ? off : on);
  choice.solved_in_full = true;
  return {};
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
  const double axis = price_of(choice.prices, 0.0) <= price_of(choice.prices, 90.0) ? 0.0 : 90.0;
  choice.direction_deg = axis;
  if (clearly_cheaper(pricing, price_of(choice.prices, best), price_of(choice.prices, axis))) {
    SUBFEED_TRY(confirm_in_full(mesh, cl_points, path_points, pricing, best, on_solve, choice));
  }
  return choice;
}

} // namespace subfeed::geometry
