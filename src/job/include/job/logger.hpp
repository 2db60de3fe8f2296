#pragma once
// Where the front's words go: results and progress to stdout (none with --quiet, more with
// --verbose), errors and warnings to stderr always, and everything, timestamped, to the
// --log file when one is given. One Logger per process, owned by main and passed down.

#include "base/error.hpp"

#include <filesystem>
#include <fstream>
#include <iosfwd>
#include <string_view>

namespace subfeed::job {

enum class Verbosity { quiet, normal, verbose };

class Logger {
public:
  Logger(Verbosity verbosity, std::ostream& out, std::ostream& err);

  // Appends to `path`; a log that cannot be opened is a bad-input error naming it.
  [[nodiscard]] Expected<void> open_log(const std::filesystem::path& path);

  void info(std::string_view line);    // normal output
  void detail(std::string_view line);  // only with --verbose
  void warning(std::string_view line); // always, to stderr
  void error(const Error& error);      // always, one line, to stderr

  [[nodiscard]] Verbosity verbosity() const { return verbosity_; }

private:
  void to_log(std::string_view level, std::string_view line);

  Verbosity verbosity_;
  std::ostream& out_;
  std::ostream& err_;
  std::ofstream log_;
};

} // namespace subfeed::job
