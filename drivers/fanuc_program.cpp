#include "drivers/fanuc_program.hpp"

#include <cctype>
#include <cstdio>

namespace subfeed::drivers {

bool iso840_character(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == ' ' || c == '+' || c == '-' ||
         c == '.' || c == '/' || c == '(' || c == ')' || c == '#' || c == '*' || c == ';' ||
         c == '=' || c == '%' || c == ':';
}

Expected<void> check_tape_block(std::string_view text, const Where& where) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (!iso840_character(c)) {
      char shown[24];
      std::snprintf(shown, sizeof shown, std::isprint(c) != 0 ? "'%c'" : "byte 0x%02X", c);
      return fail(ErrorCode::bad_input,
                  std::string(shown) +
                      " is not an ISO 840 tape character (the control would raise a TH alarm)",
                  where);
    }
  }
  return {};
}

Expected<FanucProgram> FanucProgram::open(const std::filesystem::path& path) {
  FanucProgram program(path.string());
  program.in_.open(path, std::ios::binary);
  if (!program.in_) {
    return fail(ErrorCode::bad_input, "cannot open program file", {program.name_, 0, {}});
  }
  return program;
}

Expected<void> FanucProgram::rewind() {
  in_.clear();
  in_.seekg(0);
  line_ = 0;
  if (!in_) {
    return fail(ErrorCode::bad_input, "cannot rewind program file", {name_, 0, {}});
  }
  return {};
}

Expected<bool> FanucProgram::next(FanucBlock& block) {
  std::string raw;
  while (std::getline(in_, raw)) {
    ++line_;
    while (!raw.empty() && (raw.back() == '\r' || raw.back() == ' ' || raw.back() == '\t')) {
      raw.pop_back();
    }
    if (raw.empty()) {
      continue;
    }
    SUBFEED_TRY(check_tape_block(raw, {name_, static_cast<int>(line_), {}}));
    block.line = line_;
    block.text = std::move(raw);
    return true;
  }
  if (in_.bad()) {
    return fail(ErrorCode::bad_input, "read error", {name_, static_cast<int>(line_), {}});
  }
  return false;
}

Expected<FanucScan> FanucProgram::scan() {
  SUBFEED_TRY(rewind());
  FanucScan scan;
  FanucBlock block;
  while (true) {
    SUBFEED_TRY_ASSIGN(const bool more, next(block));
    if (!more) {
      break;
    }
    scan.framed = scan.framed || (scan.blocks == 0 && block.text == "%");
    ++scan.blocks;
    scan.bytes += static_cast<long>(block.text.size()) + 1;
  }
  SUBFEED_TRY(rewind());
  return scan;
}

} // namespace subfeed::drivers
