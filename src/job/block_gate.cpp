#include "job/block_gate.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::job {

namespace {

constexpr int rapid_samples = 8;
constexpr double rapid_turn_deg = 0.5; // a pose at least each this much rotary turn

std::array<double, 3> unit(const std::array<double, 3>& v) {
  const double n = std::hypot(v[0], v[1], v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

} // namespace

BlockGate::BlockGate(const post::MachineConfig& machine, geometry::MotionGate gate)
    : kinematics_(post::make_kinematics(machine)), gate_(std::move(gate)) {}

Expected<void> BlockGate::pass(const post::ToolPose& pose, const post::MotionBlock& block) {
  cl::ClPose p;
  p.tip = pose.tip;
  p.axis = pose.axis;
  p.kind = block.motion == post::Motion::rapid ? cl::MoveKind::rapid : cl::MoveKind::feed;
  p.line = block.cl_line;
  auto checked = gate_.check(p);
  if (!checked) {
    auto error = std::move(checked).error();
    error.message = "as posted, the joints moving from block to block: " + error.message;
    return std::unexpected(std::move(error));
  }
  return {};
}

Expected<void> BlockGate::check(const post::MotionBlock& block) {
  const post::JointPosition from = joints_;
  const bool was_known = std::ranges::all_of(known_, [](bool k) { return k; });
  for (std::size_t i = 0; i < 6; ++i) {
    if (block.axes[i]) {
      joints_[i] = *block.axes[i];
      if (i < 3) {
        known_[i] = true;
      }
    }
  }
  if (!std::ranges::all_of(known_, [](bool k) { return k; })) {
    return {};
  }
  // The pose at t along the block: the joints' blend, or under tool-centre-point control the
  // tip straight from the last and the axis from the angles or the vector.
  const auto at = [&](double t) {
    post::JointPosition j{};
    for (std::size_t i = 0; i < 6; ++i) {
      j[i] = from[i] + t * (joints_[i] - from[i]);
    }
    post::ToolPose p = kinematics_->forward(j);
    if (block.tcp) {
      for (std::size_t i = 0; i < 3; ++i) {
        p.tip[i] = was_known ? last_.tip[i] + t * (joints_[i] - last_.tip[i]) : joints_[i];
      }
      if (block.vector) {
        const auto v = unit(*block.vector);
        p.axis = t >= 1.0 || !was_known ? v
                                        : unit({last_.axis[0] + t * (v[0] - last_.axis[0]),
                                                last_.axis[1] + t * (v[1] - last_.axis[1]),
                                                last_.axis[2] + t * (v[2] - last_.axis[2])});
      }
    }
    return p;
  };
  int samples = 1;
  if (was_known && block.motion == post::Motion::rapid) {
    samples = rapid_samples;
    for (std::size_t r = 3; r < 6; ++r) {
      samples = std::max(
          samples, static_cast<int>(std::ceil(std::abs(joints_[r] - from[r]) / rapid_turn_deg)));
    }
  }
  for (int k = 1; k <= samples; ++k) {
    const auto pose = at(static_cast<double>(k) / samples);
    SUBFEED_TRY(pass(pose, block));
    last_ = pose;
  }
  return {};
}

} // namespace subfeed::job
