#pragma once
// How long a machine takes for posted motion blocks, for a job's ETA: feed moves at their
// feed (G94: programmed length over F, lengths combining all axes as the control does, deg
// counted as mm; G93: 1/F minutes), rapids at the slowest moved axis's max_feed, and an
// acceleration ramp to and from rest (v / a each way) wherever the machine must stop: at
// rapids, and where a feed move reverses or turns a corner sharper than 90 degrees. An
// estimate, not a simulation: a control's look-ahead blends more and so finishes earlier.

#include "post/machine_config.hpp"
#include "post/motion_block.hpp"

#include <array>

namespace subfeed::job {

class MotionTimeModel {
public:
  explicit MotionTimeModel(const post::MachineConfig& machine, double acceleration_mm_s2 = 500.0);

  // Minutes the block takes, starting where the previous one ended.
  [[nodiscard]] double add(const post::MotionBlock& block);

private:
  const post::MachineConfig* machine_;
  double acceleration_; // mm/min^2
  std::array<double, 6> at_{};
  std::array<double, 6> last_direction_{};
  bool at_rest_ = true;
};

} // namespace subfeed::job
