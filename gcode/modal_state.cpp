#include "gcode/modal_state.hpp"

#include "gcode/words.hpp"

#include <cmath>
#include <string>

namespace subfeed::gcode {

namespace {

// Fanuc M-series modal groups of the G codes that matter for a restart; 0: not modal here.
int g_group(double g) {
  const auto is = [g](double code) { return std::abs(g - code) < 1e-6; };
  if (is(0) || is(1) || is(2) || is(3)) {
    return 1;
  }
  if (is(17) || is(18) || is(19)) {
    return 2;
  }
  if (is(90) || is(91)) {
    return 3;
  }
  if (is(93) || is(94) || is(95)) {
    return 5;
  }
  if (is(20) || is(21)) {
    return 6;
  }
  if (is(40) || is(41) || is(42)) {
    return 7;
  }
  if (is(43) || is(44) || is(49) || is(43.4) || is(43.5)) {
    return 8;
  }
  if ((g >= 54 && g <= 59.0001) || is(54.1)) {
    return 14;
  }
  return 0;
}

std::string g_text(const std::string& value) {
  return "G" + value;
}

} // namespace

Expected<void> ModalState::apply(std::string_view block, const Where& where) {
  bool length_word = false;
  std::optional<std::string> h;
  auto words = split_words(block);
  if (!words) {
    return fail(ErrorCode::bad_input, words.error().message, where);
  }
  for (const Word& w : *words) {
    switch (w.letter) {
    case 'G':
      if (const int group = g_group(w.value); group != 0) {
        groups_[group] = g_text(w.number);
        length_word = length_word || group == 8;
      }
      break;
    case 'F':
      feed_ = w.number;
      break;
    case 'S':
      speed_ = w.number;
      break;
    case 'T':
      tool_ = w.number;
      break;
    case 'H':
      h = w.number;
      break;
    case 'M': {
      const auto m = static_cast<int>(w.value);
      if (m == 3 || m == 4 || m == 5) {
        spindle_ = "M0" + std::to_string(m);
      } else if (m == 7 || m == 8 || m == 9) {
        coolant_ = "M0" + std::to_string(m);
      } else if (m == 6) {
        tool_changed_ = true;
      }
      break;
    }
    default:
      break;
    }
  }
  if (length_word) {
    length_offset_ = h;
  }
  return {};
}

Expected<std::vector<std::string>> ModalState::restore_blocks(const Where& restart) const {
  const auto group = [this](int g) -> std::string {
    const auto it = groups_.find(g);
    return it == groups_.end() ? std::string() : it->second;
  };
  const std::string comp = group(7);
  if (comp == "G41" || comp == "G42") {
    return fail(ErrorCode::bad_input,
                "cannot restart inside cutter radius compensation (" + comp +
                    "); restart at a block where G40 is in effect",
                restart);
  }
  const std::string length = group(8);
  if (length == "G43.5") {
    return fail(ErrorCode::bad_input,
                "cannot restart inside G43.5 (its state is the tool vector); restart before it or "
                "after G49",
                restart);
  }
  std::vector<std::string> blocks;
  std::string setup;
  for (const int g : {6, 2, 3, 5, 14}) {
    const std::string code = group(g);
    setup += code.empty() ? "" : (setup.empty() ? "" : " ") + code;
  }
  if (!setup.empty()) {
    blocks.push_back(setup);
  }
  if (tool_) {
    blocks.push_back("T" + *tool_ + (tool_changed_ ? " M06" : ""));
  }
  if (!length.empty() && length != "G49" && length_offset_) {
    blocks.push_back(length + " H" + *length_offset_);
  } else if (length == "G49") {
    blocks.push_back("G49");
  }
  if (spindle_) {
    blocks.push_back((speed_ ? "S" + *speed_ + " " : std::string()) + *spindle_);
  }
  if (coolant_) {
    blocks.push_back(*coolant_);
  }
  std::string motion = group(1);
  if (feed_) {
    motion += (motion.empty() ? "" : " ") + std::string("F") + *feed_;
  }
  if (!motion.empty()) {
    blocks.push_back(motion);
  }
  return blocks;
}

} // namespace subfeed::gcode
