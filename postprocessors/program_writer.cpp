#include "post/program_writer.hpp"

#include "base/decimal_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

namespace subfeed::post {

namespace {

// Characters of ISO 840 a Fanuc-style control takes on tape (letters, digits and these).
constexpr std::string_view iso840_symbols = " +-./%(),:#*=[]&'?@_;$\"";

bool is_iso840(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         iso840_symbols.find(c) != std::string_view::npos;
}

} // namespace

ProgramWriter::ProgramWriter(ProgramOptions options, const AxisSet& axes, Sink sink)
    : options_(std::move(options)), axes_(axes), sink_(std::move(sink)) {}

std::string ProgramWriter::comment(std::string_view text) const {
  std::string out = "(";
  for (const char c : text) {
    const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const bool fits = options_.dialect == Dialect::fanuc ? is_iso840(upper) : std::isprint(upper);
    out += fits && upper != '(' && upper != ')' ? upper : ' ';
  }
  return out + ")";
}

Expected<void> ProgramWriter::emit(std::string line, long cl_line, bool link) {
  if (options_.line_numbers && options_.dialect != Dialect::grbl && !line.empty() && line != "%" &&
      line.front() != 'O') {
    block_number_ = block_number_ % 99999 + 1; // N has five digits
    line.insert(0, "N" + std::to_string(block_number_) + " ");
  }
  if (static_cast<int>(line.size()) > options_.line_length) {
    return fail(ErrorCode::bad_input,
                "block '" + line + "' is longer than the controller's " +
                    std::to_string(options_.line_length) + " characters (controller.line_length)",
                {{}, static_cast<int>(cl_line), {}});
  }
  if (options_.dialect == Dialect::fanuc) {
    for (const char c : line) {
      if (!is_iso840(c)) {
        return fail(ErrorCode::bad_input, "character outside ISO 840 in block '" + line + "'",
                    {{}, static_cast<int>(cl_line), {}});
      }
    }
  }
  ++lines_;
  sink_(line, cl_line, link);
  return {};
}

Expected<void> ProgramWriter::begin() {
  if (options_.dialect == Dialect::fanuc) {
    SUBFEED_TRY(emit("%", 0, true));
    auto o_line = "O" + std::to_string(10000 + options_.program_number).substr(1);
    if (options_.comments && !options_.title.empty()) {
      o_line += comment(options_.title);
    }
    SUBFEED_TRY(emit(std::move(o_line), 0, true));
  } else if (options_.comments && !options_.title.empty()) {
    SUBFEED_TRY(emit(comment(options_.title), 0, true));
  }
  std::string modes = "G21 G90 G94 G17";
  if (options_.dialect != Dialect::grbl) {
    modes += " G40 G49 G80"; // cancel cutter compensation, length offset, canned cycles
  }
  feed_mode_ = 94;
  SUBFEED_TRY(emit(std::move(modes), 0, true));
  if (options_.dialect == Dialect::linuxcnc) {
    std::string blend = "G64 P";
    append_decimal(blend, options_.blend_tolerance, options_.decimals + 1);
    SUBFEED_TRY(emit(std::move(blend), 0, true));
  }
  if (options_.spindle_rpm) {
    std::string spindle = "S";
    append_decimal(spindle, *options_.spindle_rpm, 0);
    spindle.pop_back(); // S is an integer word
    SUBFEED_TRY(emit(spindle + " M3", 0, true));
  }
  return {};
}

void ProgramWriter::append_modes(std::string& line, const MotionBlock& block) {
  if (block.tcp != tcp_) {
    if (block.tcp) {
      line += block.vector ? "G43.5 H" : "G43.4 H";
      line += std::to_string(options_.tool_length_offset) + ' ';
    } else {
      line += "G49 ";
    }
    tcp_ = block.tcp;
    motion_ = -1; // the control wants the motion word with the mode change
  }
  const int motion = block.motion == Motion::rapid ? 0 : 1;
  if (motion != motion_) {
    line += motion == 0 ? "G0 " : "G1 ";
    motion_ = motion;
  }
  if (block.motion == Motion::linear) {
    const int mode = block.feed_mode == FeedMode::inverse_time ? 93 : 94;
    if (mode != feed_mode_) {
      line += mode == 93 ? "G93 " : "G94 ";
      feed_mode_ = mode;
      last_feed_.clear(); // F must be given again after a feed mode change
    }
  }
}

void ProgramWriter::append_axis_words(std::string& line, const MotionBlock& block) {
  for (std::size_t i = 0; i < block.axes.size(); ++i) {
    if (!block.axes[i] || !axes_[i]) {
      continue;
    }
    std::string word(1, axis_letters[i]);
    append_decimal(word, *block.axes[i], options_.decimals + (is_rotary_axis(i) ? 1 : 0));
    if (word != last_axis_[i]) {
      line += word + ' ';
      last_axis_[i] = std::move(word);
    }
  }
  if (block.vector) {
    for (std::size_t i = 0; i < 3; ++i) {
      std::string word(1, "IJK"[i]);
      append_decimal(word, (*block.vector)[i], 6);
      if (word != last_vector_[i]) {
        line += word + ' ';
        last_vector_[i] = std::move(word);
      }
    }
  }
}

Expected<void> ProgramWriter::write(const MotionBlock& block) {
  std::string words;
  append_axis_words(words, block);
  if (words.empty()) {
    return {}; // nothing moves: no block (a mode change waits for the next motion)
  }
  std::string line;
  append_modes(line, block);
  line += words;
  if (block.motion == Motion::linear) {
    std::string feed = "F";
    // Inverse-time F spans 0.001 to 1e6 per minute: keep five significant digits.
    const int digits =
        block.feed_mode == FeedMode::inverse_time
            ? std::clamp(4 - static_cast<int>(std::floor(std::log10(block.feed))), 0, 6)
            : 1;
    // Rounded down: a feed a hair too slow is harmless, one too fast can exceed max_feed.
    const double scale = std::pow(10.0, digits);
    append_decimal(feed, std::max(std::floor(block.feed * scale), 1.0) / scale, digits);
    if (feed != last_feed_ || block.feed_mode == FeedMode::inverse_time) {
      line += feed;
      last_feed_ = std::move(feed);
    }
  }
  while (!line.empty() && line.back() == ' ') {
    line.pop_back();
  }
  return emit(std::move(line), block.cl_line, block.link);
}

Expected<void> ProgramWriter::end() {
  if (tcp_) {
    SUBFEED_TRY(emit("G49", 0, true));
    tcp_ = false;
  }
  if (feed_mode_ != 94) {
    SUBFEED_TRY(emit("G94", 0, true));
  }
  if (options_.spindle_rpm) {
    SUBFEED_TRY(emit("M5", 0, true));
  }
  if (options_.dialect == Dialect::fanuc) {
    SUBFEED_TRY(emit("M30", 0, true));
    return emit("%", 0, true);
  }
  return emit("M2", 0, true);
}

} // namespace subfeed::post
