#pragma once
// Turns CL poses into motion blocks for one machine, one pose at a time (memory does not
// depend on the program's length):
//  - joints from the kinematics, the solution chosen by a RotaryTracker; the starting
//    solution from a look-ahead pass over the whole operation (the one that needs the
//    fewest repositionings, then the preferred tilt);
//  - feed moves split until the tool tip, moving joint-linearly as the control moves it,
//    stays within `tolerance` of the straight CL segment and the tool axis within
//    `axis_tolerance` of the CL axes' great-circle interpolation;
//  - feeds: G93 inverse time for blocks that turn a rotary axis, G94 otherwise, each block
//    slowed where an axis would exceed its max_feed;
//  - positioning that turns a rotary axis goes up to the safe Z first; where the limits
//    force another solution mid-cut: retract along the tool axis, up to safe Z, turn,
//    re-approach the same point and go on;
//  - with tool-centre-point control (G43.4/G43.5) X Y Z are the tip: no splitting.

#include "base/error.hpp"
#include "cl/cl_pose.hpp"
#include "cl/cl_reader.hpp"
#include "post/kinematics.hpp"
#include "post/motion_block.hpp"
#include "post/rotary_tracker.hpp"

#include <functional>
#include <optional>

namespace subfeed::post {

struct PostOptions {
  double tolerance = 0.002;     // mm, tool tip from the straight CL segment
  double axis_tolerance = 0.05; // deg, tool axis from the interpolated CL axis
  TcpMode tcp = TcpMode::off;
  int decimals = 3; // of the program's mm words: their rounding comes out of the tolerance
};

struct PostStats {
  long poses = 0;
  long blocks = 0;
  long splits = 0;            // extra blocks from linearization
  long repositions = 0;       // retract-turn-re-approach sequences forced by limits
  long cone_poses = 0;        // poses where C was held near the pole
  double max_axis_hold = 0.0; // deg, largest axis error accepted inside the cone
};

class PostProcessor {
public:
  using BlockSink = std::function<Expected<void>(const MotionBlock&)>;

  PostProcessor(const MachineConfig& machine, const Kinematics& kinematics, PostOptions options,
                BlockSink sink);

  // The look-ahead: reads the whole operation once to choose the starting solution, then
  // rewinds the reader. Optional; without it the start follows the preferred tilt.
  [[nodiscard]] Expected<void> choose_start(cl::ClReader& reader);
  [[nodiscard]] Expected<void> add(const cl::ClPose& pose);
  // Retract from the last pose and go up to the safe Z.
  [[nodiscard]] Expected<void> finish();

  [[nodiscard]] const PostStats& stats() const { return stats_; }

private:
  struct Placed {
    cl::ClPose pose;
    JointPosition joints{};
  };
  [[nodiscard]] Expected<void> emit(MotionBlock block, const JointPosition* joints = nullptr);
  [[nodiscard]] Expected<void> rapid_words(const JointPosition& target,
                                           std::initializer_list<std::size_t> axes, long line);
  [[nodiscard]] Expected<void> position(const Placed& target, bool feed_in);
  [[nodiscard]] Expected<void> retract(const Placed& from);
  [[nodiscard]] Expected<void> up_to_safe_z(long line);
  [[nodiscard]] Expected<void> cut_segment(const Placed& from, const Placed& to, bool link);
  [[nodiscard]] bool within_tolerance(const Placed& from, const Placed& to) const;
  [[nodiscard]] Placed midpoint(const Placed& from, const Placed& to) const;
  [[nodiscard]] Placed offset_along_axis(const Placed& at, double distance) const;
  [[nodiscard]] MotionBlock block_for(const Placed& target, Motion motion) const;
  [[nodiscard]] double safe_z() const;
  [[nodiscard]] double rounded(double value, std::size_t axis) const;
  [[nodiscard]] double programmed_length(const Placed& a, const Placed& b) const;
  [[nodiscard]] double block_minutes(const Placed& a, const Placed& b) const;
  [[nodiscard]] Expected<std::vector<JointPosition>> pole_start_candidates(cl::ClReader& reader,
                                                                           const cl::ClPose& first);
  [[nodiscard]] long count_repositions(cl::ClReader& reader, const JointPosition& start);

  const MachineConfig* machine_;
  const Kinematics* kinematics_;
  PostOptions options_;
  BlockSink sink_;
  RotaryTracker tracker_;
  std::optional<JointPosition> start_;
  std::optional<Placed> last_;
  JointPosition machine_at_{}; // where the last block left the joints
  double split_tolerance_;     // mm: the tolerance less the output's rounding
  PostStats stats_;
};

} // namespace subfeed::post
