#pragma once
// Where the Fanuc drip feed takes a program's blocks from: a file on disk (FanucProgram) or
// a program still being posted (LiveBlocks). Blocks are the text as written, numbered as
// lines of the program, and already checked against the ISO 840 character set.

#include "base/error.hpp"

#include <chrono>
#include <string>
#include <string_view>

namespace subfeed::drivers {

struct FanucBlock {
  long line = 0; // 1-based line in the program text
  std::string text;
};

struct FanucScan {
  long blocks = 0; // non-blank lines, '%' lines included; 0 when not known ahead
  long bytes = 0;
  bool framed = false; // the first block is '%'
};

class BlockSource {
public:
  virtual ~BlockSource() = default;
  [[nodiscard]] virtual const std::string& name() const = 0;
  [[nodiscard]] virtual Expected<FanucScan> scan() = 0;
  [[nodiscard]] virtual Expected<void> rewind() = 0;
  // Fills `block` with the next non-blank line; false at the end of the program.
  [[nodiscard]] virtual Expected<bool> next(FanucBlock& block) = 0;
  // Whether next() answers without waiting on whoever writes the program, waiting up to
  // `wait` for that (LineSource::ready). A file is always ready.
  [[nodiscard]] virtual bool ready(std::chrono::milliseconds /*wait*/) { return true; }
};

// ISO 840 tape characters: capitals, digits, space and + - . / ( ) # * ; = % :
[[nodiscard]] bool iso840_character(unsigned char c);
// An error naming `where` and the first character outside ISO 840.
[[nodiscard]] Expected<void> check_tape_block(std::string_view text, const Where& where);

} // namespace subfeed::drivers
