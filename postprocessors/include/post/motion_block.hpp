#pragma once
// One motion of the posted program, before it is spelled in a dialect: which words it
// moves, how fast, and where it came from. Joint values are machine coordinates (mm, deg);
// under tool-centre-point control X Y Z are the tool tip in the work frame instead.

#include <array>
#include <optional>

namespace subfeed::post {

enum class Motion { rapid, linear };
enum class FeedMode { per_minute, inverse_time };
enum class TcpMode { off, angles, vector }; // G43.4 with A/C words; G43.5 with I J K

struct MotionBlock {
  Motion motion = Motion::linear;
  std::array<std::optional<double>, 6> axes{}; // X Y Z A B C words; unset: not moved
  std::optional<std::array<double, 3>> vector; // G43.5 tool axis I J K
  FeedMode feed_mode = FeedMode::per_minute;
  double feed = 0.0; // linear moves: mm/min (G94) or 1/min (G93)
  bool tcp = false;  // X Y Z are the tool tip under G43.4/G43.5
  long cl_line = 0;  // CL line this block serves (0: program frame)
  bool link = false; // off the CL path: approach, retract, reposition
};

} // namespace subfeed::post
