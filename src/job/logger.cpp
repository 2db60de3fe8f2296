#include "job/logger.hpp"

#include <chrono>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <ostream>

namespace subfeed::job {

Logger::Logger(Verbosity verbosity, std::ostream& out, std::ostream& err)
    : verbosity_(verbosity), out_(out), err_(err) {}

Expected<void> Logger::open_log(const std::filesystem::path& path) {
  log_.open(path, std::ios::app);
  if (!log_) {
    return fail(ErrorCode::bad_input, "cannot open log file for appending",
                {path.string(), 0, "--log"});
  }
  return {};
}

void Logger::to_log(std::string_view level, std::string_view line) {
  if (log_.is_open()) {
    const auto now =
        std::chrono::floor<std::chrono::milliseconds>(std::chrono::system_clock::now());
    log_ << fmt::format("{:%FT%T}Z {} {}\n", now, level, line) << std::flush;
  }
}

void Logger::info(std::string_view line) {
  to_log("info", line);
  if (verbosity_ != Verbosity::quiet) {
    out_ << line << '\n';
  }
}

void Logger::detail(std::string_view line) {
  to_log("detail", line);
  if (verbosity_ == Verbosity::verbose) {
    out_ << line << '\n';
  }
}

void Logger::warning(std::string_view line) {
  to_log("warning", line);
  err_ << "subfeed: warning: " << line << '\n';
}

void Logger::error(const Error& error) {
  const std::string line = error.describe();
  to_log("error", line);
  err_ << "subfeed: error: " << line << std::endl;
}

} // namespace subfeed::job
