#include "job/restart_approach.hpp"

#include "gcode/modal_state.hpp"
#include "post/rotary_tracker.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>

namespace subfeed::job {

namespace {

post::ToolPose along_axis(post::ToolPose pose, double distance) {
  for (std::size_t i = 0; i < 3; ++i) {
    pose.tip[i] += distance * pose.axis[i];
  }
  return pose;
}

std::string move_line(const char* g, const Joints& j, const post::AxisSet& axes,
                      std::initializer_list<std::size_t> which, int decimals) {
  std::string line = g;
  for (const auto i : which) {
    if (axes[i]) {
      line +=
          fmt::format(" {}{:.{}f}", post::axis_letters[i], j[i], i < 3 ? decimals : decimals + 1);
    }
  }
  return line;
}

} // namespace

Joints machine_joints(const post::MachineConfig& machine, const LineEnd& end) {
  if (!end.tcp) {
    return end.words;
  }
  const auto k = post::make_kinematics(machine);
  const post::RotaryTracker solutions(*k, machine);
  Joints angles{};
  for (std::size_t i = 3; i < 6; ++i) {
    angles[i] = end.words[i];
  }
  const post::ToolPose pose{{end.words[0], end.words[1], end.words[2]}, k->forward(angles).axis};
  return solutions.nearest(pose, angles);
}

bool tool_axis_fixed(const post::MachineConfig& machine) {
  return machine.kinematics != post::KinematicsType::xyzac_head;
}

std::vector<std::string> approach_blocks(const post::MachineConfig& m, const Approach& a) {
  const auto k = post::make_kinematics(m);
  const post::RotaryTracker solutions(*k, m);
  const int d = m.controller.decimals;
  const double safe_z = m.post.safe_z.value_or(m.axes[2]->max);
  const std::string f = fmt::format(" F{:.0f}", a.feed);
  std::vector<std::string> blocks;
  if (a.tcp) {
    blocks.emplace_back("G49");
  }
  blocks.emplace_back("G94");
  Joints up = a.to;
  if (a.from) {
    const Joints retract = solutions.nearest(along_axis(k->forward(*a.from), a.clearance), *a.from);
    blocks.push_back(move_line("G1", retract, m.axes, {0, 1, 2, 3, 4, 5}, d) + f);
    up = retract;
    up[2] = std::max(safe_z, retract[2]);
  } else {
    up[2] = safe_z;
  }
  Joints turned = up;
  for (std::size_t i = 3; i < 6; ++i) {
    turned[i] = a.to[i];
  }
  const Joints above = solutions.nearest(along_axis(k->forward(a.to), a.clearance), a.to);
  Joints over = above;
  over[2] = up[2];
  blocks.push_back(move_line("G0", up, m.axes, {2}, d));
  if (m.axes[3] || m.axes[4] || m.axes[5]) {
    blocks.push_back(move_line("G0", turned, m.axes, {3, 4, 5}, d));
  }
  blocks.push_back(move_line("G0", over, m.axes, {0, 1}, d));
  blocks.push_back(move_line("G0", above, m.axes, {0, 1, 2, 3, 4, 5}, d));
  blocks.push_back(move_line("G1", a.to, m.axes, {0, 1, 2, 3, 4, 5}, d) + f);
  return blocks;
}

Expected<std::vector<std::string>> restore_blocks(const std::string& program, long after) {
  gcode::ModalState modal;
  std::ifstream in(program);
  std::string text;
  for (long n = 1; n <= after && std::getline(in, text); ++n) {
    SUBFEED_TRY(modal.apply(text, {program, static_cast<int>(n), {}}));
  }
  return modal.restore_blocks({program, static_cast<int>(after + 1), {}});
}

} // namespace subfeed::job
