#pragma once
// How `send` (and later `run`) shows a stream to its user: a one-line progress display on a
// terminal (acknowledged/total, %, elapsed, ETA, controller state), JSON events one per line
// for scripts (--json), or nothing (--quiet). Everything also goes to the --log file.

#include "drivers/grbl_streamer.hpp"
#include "job/logger.hpp"

#include <chrono>

namespace subfeed::cli {

using job::Logger;

// JSON string contents: controller messages may carry quotes, backslashes or noise bytes.
[[nodiscard]] std::string json_escape(std::string_view text);
// The controller's state for a display: "Run", "Hold:0", or the link's state for DNC.
[[nodiscard]] std::string state_text(const drivers::StreamProgress& p);

class StreamReporter final : public drivers::StreamObserver {
public:
  StreamReporter(Logger& log, bool json);
  ~StreamReporter() override;

  void connected(const drivers::ControllerInfo& info) override;
  void progress(const drivers::StreamProgress& progress) override;
  void message(std::string_view line) override;
  void line_error(const drivers::LineError& error) override;
  void phase(std::string_view name) override;

  // After the stream: the summary line, or the error as a JSON event.
  // `baud` and `bits_per_character` give the wire's capacity, for the link use.
  void finished(const drivers::StreamSummary& summary, std::optional<int> baud,
                int bits_per_character);
  void failed(const Error& error);
  void end_progress_line();

private:
  Logger& log_;
  bool json_;
  bool terminal_;
  bool progress_shown_ = false;
  std::chrono::steady_clock::time_point last_update_{};
  std::string last_state_;
};

} // namespace subfeed::cli
