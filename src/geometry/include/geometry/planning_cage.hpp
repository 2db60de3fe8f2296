#pragma once
// The cage the planner meshes: the user's, or the user's subdivided a level or more where
// that meshes the same limit surface within the same tolerance with clearly fewer
// vertices (cage_refinement.hpp). Each cage face is meshed at one rate, the rate its most
// curved spot needs, so a few large faces with tight corners cost more than their
// refinement, whose children each take their own rate.
//
// The choice is predicted, not tried: per face the rate the tolerance needs (not capped),
// squared and summed. A level is taken while it cuts that sum by a quarter or more, up to
// `max_levels`. Measured on a 1,640-face body shell at H 0.01: 1.32 M vertices as given,
// 0.82 M at one level, 0.58 M at two.

#include "base/error.hpp"
#include "geometry/cage.hpp"
#include "geometry/limit_surface.hpp"

#include <optional>

namespace subfeed::geometry {

struct PlanningCage {
  Cage cage;
  LimitSurface surface;
  int levels = 0; // uniform subdivision steps taken
};

// Nothing when the user's cage is best as it is.
[[nodiscard]] Expected<std::optional<PlanningCage>> planning_cage(const Cage& cage,
                                                                  const LimitSurface& surface,
                                                                  double chord_tolerance,
                                                                  int max_levels,
                                                                  double min_edge_mm = 0.0);

// The predicted vertex count of a mesh of `surface` within `chord_tolerance` (mm), cells no
// shorter than `min_edge_mm` (rates_for_tolerance).
[[nodiscard]] double predicted_vertices(const LimitSurface& surface, double chord_tolerance,
                                        double min_edge_mm = 0.0);

} // namespace subfeed::geometry
