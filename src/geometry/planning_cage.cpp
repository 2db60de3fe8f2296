#include "geometry/planning_cage.hpp"

#include "geometry/cage_refinement.hpp"
#include "geometry/surface_mesh.hpp"

namespace subfeed::geometry {

namespace {

// The rate a face may need before the estimate means nothing: far past any mesh made.
constexpr int uncapped_rate = 1 << 14;
// A level must cut the predicted vertices to this share of the last to be taken.
constexpr double worth_it = 0.75;

} // namespace

double predicted_vertices(const LimitSurface& surface, double chord_tolerance,
                          double min_edge_mm) {
  double sum = 0.0;
  for (const int rate :
       rates_for_tolerance(surface, chord_tolerance, uncapped_rate, 0.0, min_edge_mm)) {
    sum += static_cast<double>(rate) * rate;
  }
  return sum;
}

Expected<std::optional<PlanningCage>> planning_cage(const Cage& cage, const LimitSurface& surface,
                                                    double chord_tolerance, int max_levels,
                                                    double min_edge_mm) {
  std::optional<PlanningCage> best;
  double last = predicted_vertices(surface, chord_tolerance, min_edge_mm);
  for (int levels = 1; levels <= max_levels; ++levels) {
    SUBFEED_TRY_ASSIGN(auto finer, refine_cage(cage, levels));
    SUBFEED_TRY_ASSIGN(auto finer_surface, LimitSurface::build(finer, surface.approx_level()));
    const double predicted = predicted_vertices(finer_surface, chord_tolerance, min_edge_mm);
    if (predicted > worth_it * last) {
      break;
    }
    last = predicted;
    best = PlanningCage{std::move(finer), std::move(finer_surface), levels};
  }
  return best;
}

} // namespace subfeed::geometry
