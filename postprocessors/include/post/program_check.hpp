#pragma once
// `subfeed check`: replays a G-code program through the machine's forward kinematics, as
// the control would move the joints, and measures what the tool tip does. Independent of
// the post's own arithmetic: it reads only the program text, the machine config, and
// optionally the CL data with the post's trace map (PROGRAM.map) to know which CL segment
// each cutting block serves. Understands the words subfeed posts write in any dialect
// (G0 G1 G17 G21 G40 G49 G64 G80 G90 G93 G94 G43.4 G43.5, N, F, S, M, comments); any other
// motion mode (arcs, canned cycles, inches, incremental) is an error naming the line.

#include "base/error.hpp"
#include "post/kinematics.hpp"
#include "post/machine_config.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <optional>

namespace subfeed::post {

struct CheckOptions {
  double tolerance = 0.002;                // mm
  double axis_tolerance = 0.05;            // deg; the machine's singularity cone is allowed on top
  int samples_per_block = 8;               // points checked inside every feed block
  std::optional<std::filesystem::path> cl; // with PROGRAM.map beside the program
  // Each pose the tool passes through, in order, in the workpiece frame, once X, Y and Z are
  // known: every motion block's end and the points between as the joints move (rapids too,
  // the joints moving together), at least samples_per_block a block and one each half
  // degree a rotary axis turns, so that straight moves between them stay within a few um of
  // the tool's path. For a caller that measures more than the tip (check --cage).
  std::function<void(const ToolPose& pose, long line, bool rapid)> on_pose;
};

struct Finding {
  double value = 0.0;
  long line = 0; // G-code line, 0 when none
};

struct CheckReport {
  long lines = 0;
  long motion_blocks = 0;
  long feed_blocks = 0;
  long cut_blocks_compared = 0;
  Finding tip_deviation;  // mm, against the CL segment
  Finding axis_deviation; // deg
  Finding max_tip_feed;   // mm/min
  long limit_violations = 0;
  Finding first_limit_violation;
  long rotary_jumps = 0; // feed blocks turning a rotary axis by more than 180 deg
  Finding first_rotary_jump;
  long over_feed = 0; // feed blocks that ask an axis for more than its max_feed
  Finding first_over_feed;
  // The largest turn of each rotary axis (A, B, C) in one feed block, deg: how smoothly the
  // rotary axes follow the tool axis while cutting.
  std::array<Finding, 3> rotary_step;
  double cutting_minutes = 0.0;
  double allowed_axis_deviation = 0.0; // deg, what the axis deviation was held to

  [[nodiscard]] bool passed(double tolerance) const;
};

[[nodiscard]] Expected<CheckReport> check_program(const std::filesystem::path& program,
                                                  const MachineConfig& machine,
                                                  const CheckOptions& options);

} // namespace subfeed::post
