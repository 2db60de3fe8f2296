#include "post/rotary_tracker.hpp"

#include "angles.hpp"

#include <cmath>
#include <cstdio>

namespace subfeed::post {

namespace {

constexpr std::size_t c_axis = 5;
constexpr double limit_slack = 1e-6; // mm or deg: round-off at a limit is not a violation
constexpr double tie = 1e-9;         // deg: rotary moves this close are equally good

ToolPose tool_pose(const cl::ClPose& pose) {
  return {pose.tip, pose.axis};
}

std::string format_value(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}

} // namespace

RotaryTracker::RotaryTracker(const Kinematics& kinematics, const MachineConfig& machine)
    : kinematics_(&kinematics), machine_(&machine), tilt_(tilt_axis(machine.kinematics)),
      cone_cos_(std::cos(machine.post.singularity_cone * radians_per_degree)) {}

bool RotaryTracker::within_limits(const JointPosition& j) const {
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto& axis = machine_->axes[i];
    if (axis && !axis->cyclic &&
        (j[i] < axis->min - limit_slack || j[i] > axis->max + limit_slack)) {
      return false;
    }
  }
  return true;
}

double RotaryTracker::rotary_distance(const JointPosition& a, const JointPosition& b) const {
  return std::abs(a[3] - b[3]) + std::abs(a[4] - b[4]) + std::abs(a[5] - b[5]);
}

ToolPose RotaryTracker::cone_pose(const ToolPose& pose, const JointPosition& near) const {
  // The axes the machine reaches with C held form a great circle through the pole; take the
  // point of it nearest the requested axis.
  JointPosition flat{};
  flat[tilt_] = 90.0;
  flat[c_axis] = near[c_axis];
  const auto d = kinematics_->forward(flat).axis;
  const auto& k = pose.axis;
  const double t = std::atan2(k[0] * d[0] + k[1] * d[1] + k[2] * d[2], k[2]);
  ToolPose held = pose;
  for (std::size_t i = 0; i < 3; ++i) {
    held.axis[i] = std::sin(t) * d[i];
  }
  held.axis[2] += std::cos(t);
  return held;
}

RotaryTracker::Candidates RotaryTracker::candidates(const ToolPose& pose,
                                                    const JointPosition& near) const {
  Candidates out;
  out.in_cone = tilt_ != 0 && std::abs(pose.axis[2]) > cone_cos_ && std::abs(pose.axis[2]) < 1.0;
  const ToolPose target = out.in_cone ? cone_pose(pose, near) : pose;
  for (auto j : kinematics_->inverse(target, near)) {
    std::vector<JointPosition> turns{j};
    for (const std::size_t r : {tilt_, c_axis}) {
      const auto& axis = machine_->axes[r];
      if (r == 0 || !axis) {
        continue;
      }
      const double nearest = j[r] + 360.0 * std::round((near[r] - j[r]) / 360.0);
      std::vector<JointPosition> next;
      for (auto t : turns) {
        if (axis->cyclic) {
          t[r] = nearest;
          next.push_back(t);
          continue;
        }
        for (double v = j[r] + 360.0 * std::ceil((axis->min - limit_slack - j[r]) / 360.0);
             v <= axis->max + limit_slack; v += 360.0) {
          t[r] = v;
          next.push_back(t);
        }
      }
      j[r] = nearest;
      turns = std::move(next);
    }
    out.unconstrained.push_back(j);
    for (const auto& t : turns) {
      if (within_limits(t)) {
        out.feasible.push_back(t);
      }
    }
  }
  return out;
}

const JointPosition* RotaryTracker::best(const std::vector<JointPosition>& options,
                                         const JointPosition& near) const {
  const JointPosition* chosen = nullptr;
  double chosen_distance = 0.0;
  const int preferred = machine_->post.preferred_tilt;
  for (const auto& j : options) {
    const double d = rotary_distance(j, near);
    const bool better = chosen == nullptr || d < chosen_distance - tie ||
                        (d < chosen_distance + tie && preferred != 0 &&
                         j[tilt_] * preferred > 0.0 && (*chosen)[tilt_] * preferred <= 0.0);
    if (better) {
      chosen = &j;
      chosen_distance = d;
    }
  }
  return chosen;
}

std::unexpected<Error> RotaryTracker::unreachable(const cl::ClPose& pose,
                                                  const JointPosition& nearest) const {
  std::string why = "the machine cannot point the tool that way";
  for (std::size_t i = 0; i < nearest.size(); ++i) {
    const auto& axis = machine_->axes[i];
    if (axis && !axis->cyclic &&
        (nearest[i] < axis->min - limit_slack || nearest[i] > axis->max + limit_slack)) {
      why = std::string(1, axis_letters[i]) + " would be " + format_value(nearest[i]) +
            " outside its travel " + format_value(axis->min) + ".." + format_value(axis->max);
      break;
    }
  }
  return fail(ErrorCode::bad_input, "pose out of the machine's reach: " + why,
              {{}, static_cast<int>(pose.line), {}});
}

Expected<std::vector<JointPosition>> RotaryTracker::start_candidates(const cl::ClPose& pose) const {
  const auto c = candidates(tool_pose(pose), current_);
  if (c.feasible.empty()) {
    if (c.unconstrained.empty()) {
      return unreachable(pose, {});
    }
    return unreachable(pose, c.unconstrained.front());
  }
  return c.feasible;
}

bool RotaryTracker::in_cone(const std::array<double, 3>& axis) const {
  return tilt_ != 0 && std::abs(axis[2]) > cone_cos_;
}

JointPosition RotaryTracker::prefer(const std::vector<JointPosition>& options) const {
  const JointPosition* j = best(options, JointPosition{});
  return j != nullptr ? *j : JointPosition{};
}

void RotaryTracker::start_at(const JointPosition& joints) {
  current_ = joints;
  started_ = true;
}

Expected<TrackedStep> RotaryTracker::step(const cl::ClPose& pose) {
  const auto c = candidates(tool_pose(pose), current_);
  const JointPosition* free = best(c.unconstrained, current_);
  const JointPosition* chosen = best(c.feasible, current_);
  if (chosen == nullptr) {
    return unreachable(pose, free != nullptr ? *free : JointPosition{});
  }
  TrackedStep step{*chosen, false, c.in_cone};
  step.reposition = started_ && free != nullptr &&
                    rotary_distance(*chosen, current_) > rotary_distance(*free, current_) + 1e-6;
  start_at(*chosen);
  return step;
}

JointPosition RotaryTracker::nearest(const ToolPose& pose, const JointPosition& near) const {
  const auto c = candidates(pose, near);
  const JointPosition* j = best(c.unconstrained, near);
  return j != nullptr ? *j : near;
}

} // namespace subfeed::post
