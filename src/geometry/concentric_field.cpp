#include "geometry/concentric_field.hpp"

#include "geometry/front_arrival.hpp"
#include "geometry/pass_insertion.hpp"
#include "geometry/vertex_groups.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace subfeed::geometry {

namespace {

// The time per mm of deformed coordinate: reference / the CL spacing needed (in a hollow
// the ball cannot reach, the flat spacing: filling in the surroundings' need there instead
// was tried and left wider wakes on the dome's corners).
std::vector<double> slowness_for(const std::vector<double>& need, const PassIntervals& intervals,
                                 double reference) {
  std::vector<double> slow(need.size());
  for (std::size_t v = 0; v < need.size(); ++v) {
    const bool own = intervals.cuts(v) && need[v] > 0.0;
    slow[v] = reference / (own ? need[v] : intervals.cl_spacing[v]);
  }
  return slow;
}

// Round a centre the level lines turn every way, which the kink measure reads as a gap of
// twice the spacing; but every point there is within half a step of the first ring.
void clear_centres(const std::vector<std::array<int, 3>>& triangles, const Deformation& d,
                   SpacingRatios& measured) {
  std::vector<char> centre(d.deformed.size(), 0);
  for (const int v : d.ring_centres) {
    centre[static_cast<std::size_t>(v)] = 1;
  }
  const auto at = [](const auto& values, int v) { return values[static_cast<std::size_t>(v)]; };
  measured.worst = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const bool inside =
        std::ranges::all_of(tri, [&](int v) { return at(d.deformed, v) < d.planes.first; });
    if (inside || std::ranges::any_of(tri, [&](int v) { return at(centre, v) != 0; })) {
      measured.ratio[t] = 0.0;
    }
    measured.worst = std::max(measured.worst, measured.ratio[t]);
  }
}

} // namespace

std::vector<int> highest_points(const std::vector<Eigen::Vector3d>& p,
                                const std::vector<std::array<int, 3>>& triangles,
                                const std::vector<char>& reachable) {
  VertexGroups pieces(p.size());
  for (const auto& t : triangles) {
    for (const int v : {t[1], t[2]}) {
      pieces.join(static_cast<std::size_t>(v), static_cast<std::size_t>(t[0]));
    }
  }
  std::vector<int> best(p.size(), -1); // per piece's root
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (reachable[v] == 0) {
      continue;
    }
    auto& b = best[pieces.root(v)];
    if (b < 0 || p[v].z() > p[static_cast<std::size_t>(b)].z()) {
      b = static_cast<int>(v);
    }
  }
  std::vector<int> out;
  std::ranges::copy_if(best, std::back_inserter(out), [](int b) { return b >= 0; });
  return out;
}

PlaneSpacing ring_levels(const std::vector<double>& arrival, double reference) {
  if (arrival.empty() || reference <= 0.0) {
    return {0.0, reference, 0};
  }
  const auto [lo, hi] = std::ranges::minmax_element(arrival);
  const double first = *lo + 0.5 * reference;
  const long planes =
      first < *hi ? static_cast<long>(std::floor((*hi - first) / reference)) + 1 : 0;
  return {first, reference, planes};
}

Deformation concentric_deformation(const std::vector<Eigen::Vector3d>& c,
                                   const std::vector<Eigen::Vector3d>& path_points,
                                   const std::vector<std::array<int, 3>>& triangles,
                                   const PassIntervals& intervals, const NeedAcross& need_across,
                                   const ConcentricSettings& settings) {
  Deformation d;
  d.reference = settings.reference;
  std::vector<char> cut(intervals.reachable.size());
  for (std::size_t v = 0; v < cut.size(); ++v) {
    cut[v] = static_cast<char>(intervals.cuts(v));
  }
  d.ring_centres = highest_points(path_points, triangles, cut);
  std::vector<double> need = intervals.cl_spacing;
  std::vector<double> arrival;
  const int rounds = need_across ? 1 + settings.rounds : 1;
  for (int round = 0; round < rounds; ++round) {
    if (round > 0) {
      need = need_across(vertex_gradients(c, triangles, arrival));
    }
    arrival =
        front_arrival(c, triangles, slowness_for(need, intervals, d.reference), d.ring_centres);
    ++d.iterations;
  }
  // Vertices no front reaches lie on pieces with nothing reachable: no rings there.
  for (double& t : arrival) {
    if (!std::isfinite(t)) {
      t = 0.0;
    }
  }
  d.deformed = std::move(arrival);
  d.planes = ring_levels(d.deformed, d.reference);
  d.chosen = d.iterations;
  PassIntervals against = intervals;
  if (need_across) {
    against.cl_spacing = need_across(vertex_gradients(c, triangles, d.deformed));
  }
  auto measured = spacing_ratios(c, triangles, d.deformed, d.planes.step, against);
  clear_centres(triangles, d, measured);
  d.insertion = pass_insertion(c, triangles, measured,
                               level_lengths(path_points, triangles, d.deformed, d.planes.step),
                               settings.insertion_margin, settings.spacing_allowance);
  d.worst_ratio = d.insertion.worst_ratio;
  return d;
}

} // namespace subfeed::geometry
