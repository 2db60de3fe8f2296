#pragma once
// Where a resumed program continues. The program's axis words are followed line by line
// (absolute mode, as subfeed posts) near the interruption; the machine is then found among
// its moves from the position a GRBL-style controller reports, or a block is found by the
// sequence number a Fanuc-style control shows (DNC reports no position).

#include "base/error.hpp"
#include "post/kinematics.hpp"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace subfeed::job {

using Joints = post::JointPosition;

struct ProgramMove {
  long line;
  Joints start, end; // the axis words before and after the line
};

struct LineEnd {
  Joints words{};   // every axis word in force after the line (under TCP: tool tip and angles)
  bool tcp = false; // G43.4 in force
};

struct ProgramWindow {
  long lines = 0;
  std::vector<ProgramMove> moves;   // the motion lines of lo..hi
  std::map<long, LineEnd> line_end; // after each line of lo - 1..hi, and after `extra`
};

// Whether a program line has an axis word (comments skipped; false for a line that is not
// words).
[[nodiscard]] bool moves_an_axis(std::string_view line);

// Lines lo..hi are searched; `extra` (0: none) is a line whose end is wanted too (--from).
[[nodiscard]] Expected<ProgramWindow> read_window(const std::string& program, long lo, long hi,
                                                  long extra);

struct RestartPoint {
  long after = 0;         // continue with the line after this one
  bool mid_block = false; // the machine stopped inside the next line's move
};

// The latest place among the window's moves where the reported machine position lies, to
// the rounding of the program's words and the report's (`decimals`, GRBL reports three): at
// the end of a move (continue after it), or inside one (run it again from its start: what it
// had cut is cut again, nothing is skipped).
[[nodiscard]] std::optional<RestartPoint>
find_machine(const ProgramWindow& window, const std::vector<double>& position, int decimals);

// The last program line up to `last_sent` that carries sequence number N`number`; failing
// that, the first numbered line after `last_sent` when it carries N`number`: a control that
// ran dry had finished every block it was sent, and the operator gives the next to run.
[[nodiscard]] Expected<long> find_sequence_number(const std::string& program, long number,
                                                  long last_sent);

} // namespace subfeed::job
