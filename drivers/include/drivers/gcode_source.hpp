#pragma once
// A G-code file read one line at a time, never whole: memory stays flat however long the
// program is. scan() reads it once before anything is sent, so that a bad line stops the
// job before the machine moves, and counts the lines that will be sent.

#include "base/error.hpp"
#include "drivers/gcode_line.hpp"

#include <filesystem>
#include <fstream>
#include <optional>

namespace subfeed::drivers {

struct SourceLine {
  long number = 0; // 1-based line in the file
  PreparedLine line;
};

struct ScanSummary {
  long lines_to_send = 0; // non-blank lines
  long bytes_to_send = 0; // including one '\n' per line
};

class GcodeSource {
public:
  [[nodiscard]] static Expected<GcodeSource> open(const std::filesystem::path& path,
                                                  LineRules rules);

  // Reads the whole file once, checking every line.
  [[nodiscard]] Expected<ScanSummary> scan();
  // Back to the first line.
  [[nodiscard]] Expected<void> rewind();
  // The next line that has something to send; nullopt at the end of the file.
  [[nodiscard]] Expected<std::optional<SourceLine>> next();

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] const LineRules& rules() const { return rules_; }
  void set_rules(const LineRules& rules) { rules_ = rules; }

private:
  GcodeSource(std::string name, LineRules rules) : name_(std::move(name)), rules_(rules) {}

  std::string name_;
  LineRules rules_;
  std::ifstream in_;
  long line_ = 0;
};

} // namespace subfeed::drivers
