#pragma once
// Pass intervals for meshes whose every vertex needs the same spacing (flat test grids):
// the CL spacing and plane interval alike, every vertex reachable.

#include "geometry/pass_intervals.hpp"

#include <cstddef>

namespace subfeed::testing {

[[nodiscard]] inline geometry::PassIntervals uniform_need(std::size_t vertices, double spacing) {
  geometry::PassIntervals in;
  in.cl_spacing.assign(vertices, spacing);
  in.plane_interval.assign(vertices, spacing);
  in.reachable.assign(vertices, 1);
  in.min_interval = in.max_interval = spacing;
  return in;
}

} // namespace subfeed::testing
