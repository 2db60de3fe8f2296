#pragma once
// The simulated controller's own reading of one G-code line, as GRBL 1.1 parses it: modal
// state (distance mode, units, feed mode, motion mode, feed), the target of a move, and the
// GRBL error code for what it refuses. Written independently of the sender's code on
// purpose: a simulator that shared the sender's parser would agree with its bugs.

#include <array>
#include <string_view>

namespace subfeed::sim {

using AxisArray = std::array<double, 6>; // X Y Z A B C: mm and deg

struct SimMove {
  bool present = false; // the line moves the machine
  bool rapid = false;
  AxisArray target{};
  double feed_mm_min = 0.0;      // for feed moves in G94
  double inverse_time_min = 0.0; // block duration in minutes for G93 moves; 0 otherwise
};

struct SimLineResult {
  int error = 0; // GRBL error code; 0 = accepted
  SimMove move;
  double dwell_s = 0.0;
  bool writes_eeprom = false; // G10 L2/L20, G28.1, G30.1
};

class GcodeInterpreter {
public:
  // Absolute words are in the work frame, `work_offset` (G54) from the machine's zero.
  explicit GcodeInterpreter(int axes, const AxisArray& work_offset = {})
      : axes_(axes), work_offset_(work_offset) {}

  // `line` has no spaces or comments; `position` (machine coordinates) is where the machine
  // will be when this line's move starts; targets are machine coordinates. Modal state
  // changes only when the line is accepted.
  [[nodiscard]] SimLineResult execute(std::string_view line, const AxisArray& position);
  void reset(); // modal state back to power-up defaults

private:
  int axes_;
  AxisArray work_offset_;
  bool absolute_ = true;
  bool inches_ = false;
  bool inverse_time_ = false;
  int motion_ = 0; // 0 rapid, 1 feed, 2/3 arcs
  double feed_ = 0.0;
};

} // namespace subfeed::sim
