#pragma once
// Spells motion blocks in one G-code dialect, one line at a time, and hands each line to a
// sink with the CL line it traces back to. Modal words are not repeated: an axis word whose
// text equals the last one written is dropped, and so are G0/G1, G93/G94 and F when they do
// not change (F is repeated on every G93 block, where it is not modal). Every line is
// checked against the controller's line length and, for Fanuc, the ISO 840 character set.
//
//   grbl      grblHAL/GRBL 1.1: no N numbers, comments only on request, M2 at the end
//   fanuc     '%', O-number, optional N numbers, M30 and '%' at the end
//   linuxcnc  rs274ngc with G64 P<tolerance> path blending, M2 at the end

#include "base/error.hpp"
#include "post/machine_config.hpp"
#include "post/motion_block.hpp"

#include <functional>
#include <string>
#include <string_view>

namespace subfeed::post {

struct ProgramOptions {
  Dialect dialect = Dialect::grbl;
  bool comments = false;
  bool line_numbers = false; // N words (fanuc and linuxcnc)
  int decimals = 3;          // mm words; degrees get one more
  int line_length = 79;
  int program_number = 1;
  std::string title;                 // program comment
  std::optional<double> spindle_rpm; // S and M3 at the start, M5 at the end
  int tool_length_offset = 1;        // H for G43.4/G43.5
  double blend_tolerance = 0.002;    // mm, LinuxCNC G64 P
};

class ProgramWriter {
public:
  // Receives each finished line (no line ending) and the CL line it serves.
  using Sink = std::function<void(std::string_view line, long cl_line, bool link)>;

  ProgramWriter(ProgramOptions options, const AxisSet& axes, Sink sink);

  [[nodiscard]] Expected<void> begin();
  [[nodiscard]] Expected<void> write(const MotionBlock& block);
  [[nodiscard]] Expected<void> end();

  [[nodiscard]] long lines() const { return lines_; }

private:
  [[nodiscard]] Expected<void> emit(std::string line, long cl_line, bool link);
  void append_axis_words(std::string& line, const MotionBlock& block);
  void append_modes(std::string& line, const MotionBlock& block);
  [[nodiscard]] std::string comment(std::string_view text) const;

  ProgramOptions options_;
  AxisSet axes_;
  Sink sink_;
  std::array<std::string, 6> last_axis_;
  std::array<std::string, 3> last_vector_;
  std::string last_feed_;
  int motion_ = -1;    // last G0/G1
  int feed_mode_ = -1; // last G93/G94
  bool tcp_ = false;
  long lines_ = 0;
  long block_number_ = 0;
};

} // namespace subfeed::post
