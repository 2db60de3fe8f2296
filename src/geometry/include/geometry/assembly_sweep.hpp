#pragma once
// The whole tool (assembly_clearance.hpp) along one move: the tip straight from t0 to t1,
// the axis a normalised blend of a0 and a1. The motion gate holds every move to it; `verify`
// measures a path with it.
//
// Method: the rules' slack is measured at a pose, then the move steps on by as much as no
// point of the tool can close in that distance (the tip's travel plus the axis's turn times
// the tool's length, per unit of the move; a blend of axes within 10 degrees turns at most
// 1.008 times as fast as evenly), and at least `least_step_mm`. The floor and the part are
// stepped apart: the floor's slack is exact and cheap, so a holder skimming the table does
// not make every step search the part. A rule broken by more than least_step_mm / 2 (plus
// the clearance's own resolution) between measured poses is always found.

#include "geometry/assembly_clearance.hpp"

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace subfeed::geometry {

struct SweepOptions {
  double cap_mm = 1.0;         // slack searched for at a pose (AssemblyClearance::slack)
  double least_step_mm = 0.02; // the shortest step along the move
  bool stop_at_first = true;   // false: measure on past broken rules (verify)
};

struct SweepFindings {
  std::optional<ClearanceViolation> first; // the first measured pose that breaks a rule
  long broken = 0;                         // measured poses that break one
};

// Each body's clearance over the move is folded into `into` (AssemblyClearance::blank()).
[[nodiscard]] SweepFindings sweep_move(const AssemblyClearance& clearance,
                                       const Eigen::Vector3d& t0, const Eigen::Vector3d& a0,
                                       const Eigen::Vector3d& t1, const Eigen::Vector3d& a1,
                                       const SweepOptions& options,
                                       std::vector<BodyClearance>* into);

} // namespace subfeed::geometry
