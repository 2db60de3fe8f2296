#include "post/rotary_tracker.hpp"

#include "angles.hpp"
#include "vector_math.hpp"

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

// Angle, degrees, between the C axis (+Z of the work) and the nearest point of the
// great-circle arc from `a` to `b`: how close a tool turning from one to the other passes
// the pole.
double pole_distance_deg(const Vec3& a, const Vec3& b) {
  const double ends = std::min(angle_deg(a, {0, 0, 1}), angle_deg(b, {0, 0, 1}));
  Vec3 n = cross(a, b);
  const double length = std::sqrt(dot(n, n));
  if (length < 1e-15) {
    return ends;
  }
  for (auto& v : n) {
    v /= length;
  }
  // The great circle's point nearest the pole, and whether it lies between a and b.
  const Vec3 p{-n[2] * n[0], -n[2] * n[1], 1.0 - n[2] * n[2]};
  if (dot(cross(a, p), n) < 0.0 || dot(cross(p, b), n) < 0.0) {
    return ends;
  }
  return std::asin(std::min(std::abs(n[2]), 1.0)) / radians_per_degree;
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

JointPosition RotaryTracker::follow(const JointPosition& start, const ToolPose& to) const {
  // Small steps along the tool's great circle, each taking the nearest solution: a step
  // that turns the rotaries more than `stride` degrees is halved, so the branch never
  // jumps (the other branch is ~180 deg away).
  constexpr double stride = 5.0;
  constexpr double finest = 1e-9;
  const ToolPose from = kinematics_->forward(start);
  JointPosition at = start;
  double t = 0.0;
  double dt = 0.125;
  while (t < 1.0) {
    const double next = std::min(1.0, t + dt);
    ToolPose p;
    for (std::size_t i = 0; i < 3; ++i) {
      p.tip[i] = from.tip[i] + next * (to.tip[i] - from.tip[i]);
    }
    p.axis = slerp(from.axis, to.axis, next);
    const JointPosition j = nearest(p, at);
    if (rotary_distance(j, at) > stride && dt > finest) {
      dt *= 0.5;
      continue;
    }
    at = j;
    t = next;
    dt *= 2.0;
  }
  return at;
}

JointPosition RotaryTracker::continuous(const ToolPose& target, const JointPosition& free) const {
  // Flipping the tilt's sign means passing through the pole, where C may turn freely; the
  // tool stays near its path only if the path itself passes within the cone. Otherwise C
  // must follow the tool's azimuth round the pole, however far that turns it.
  const bool flips = free[tilt_] * current_[tilt_] < 0.0;
  if (!started_ || tilt_ == 0 || !flips ||
      pole_distance_deg(kinematics_->forward(current_).axis, target.axis) <=
          machine_->post.singularity_cone) {
    return free;
  }
  return follow(current_, target);
}

Expected<TrackedStep> RotaryTracker::step(const cl::ClPose& pose) {
  const ToolPose target = tool_pose(pose);
  auto c = candidates(target, current_);
  const JointPosition* free = best(c.unconstrained, current_);
  JointPosition reach = free != nullptr ? continuous(target, *free) : current_;
  if (free != nullptr && rotary_distance(reach, *free) > tie) {
    c = candidates(target, reach);
  }
  const JointPosition* chosen = best(c.feasible, reach);
  if (chosen == nullptr) {
    return unreachable(pose, reach);
  }
  TrackedStep step{*chosen, false, c.in_cone};
  step.reposition = started_ && free != nullptr && rotary_distance(*chosen, reach) > 1e-6;
  start_at(*chosen);
  return step;
}

JointPosition RotaryTracker::nearest(const ToolPose& pose, const JointPosition& near) const {
  const auto c = candidates(pose, near);
  const JointPosition* j = best(c.unconstrained, near);
  return j != nullptr ? *j : near;
}

} // namespace subfeed::post
