#pragma once
// A G-code file read one line at a time, never whole: memory stays flat however long the
// program is. scan() reads it once before anything is sent, so that a bad line stops the
// job before the machine moves, and counts the lines that will be sent.

#include "base/error.hpp"
#include "drivers/gcode_line.hpp"
#include "drivers/line_source.hpp"

#include <filesystem>
#include <fstream>
#include <optional>

namespace subfeed::drivers {

class GcodeSource final : public LineSource {
public:
  [[nodiscard]] static Expected<GcodeSource> open(const std::filesystem::path& path,
                                                  LineRules rules);

  // Reads the whole file once, checking every line.
  [[nodiscard]] Expected<ScanSummary> scan() override;
  // Back to the first line.
  [[nodiscard]] Expected<void> rewind() override;
  // The next line that has something to send; nullopt at the end of the file.
  [[nodiscard]] Expected<std::optional<SourceLine>> next() override;

  [[nodiscard]] const std::string& name() const override { return name_; }
  [[nodiscard]] const LineRules& rules() const { return rules_; }
  void set_rules(const LineRules& rules) override { rules_ = rules; }

private:
  GcodeSource(std::string name, LineRules rules) : name_(std::move(name)), rules_(rules) {}

  std::string name_;
  LineRules rules_;
  std::ifstream in_;
  long line_ = 0;
};

} // namespace subfeed::drivers
