#pragma once
// A program for a Fanuc-style control, read one block at a time from disk. Blocks are sent
// as written (comments kept, nothing upper-cased: the control reads tape characters) after
// a check against ISO 840: a character the control would reject with a TH alarm stops the
// job before the first byte is sent, naming file:line. A file that starts with '%' is taken
// as framed already (leader, O-number, blocks, '%' trailer); any other gets the framing
// added by the sender.

#include "base/error.hpp"
#include "drivers/block_source.hpp"

#include <filesystem>
#include <fstream>
#include <string>

namespace subfeed::drivers {

class FanucProgram final : public BlockSource {
public:
  [[nodiscard]] static Expected<FanucProgram> open(const std::filesystem::path& path);

  [[nodiscard]] Expected<FanucScan> scan() override;
  [[nodiscard]] Expected<void> rewind() override;
  // Fills `block` with the next non-blank line; false at the end of the file.
  [[nodiscard]] Expected<bool> next(FanucBlock& block) override;
  [[nodiscard]] const std::string& name() const override { return name_; }

private:
  explicit FanucProgram(std::string name) : name_(std::move(name)) {}

  std::string name_;
  std::ifstream in_;
  long line_ = 0;
};

} // namespace subfeed::drivers
