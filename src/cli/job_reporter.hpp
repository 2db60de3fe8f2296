#pragma once
// How `run` shows a job: one progress line on a terminal with every stage in it (passes
// planned, blocks posted, lines acknowledged, % of the cutting length done, ETA from the
// motion-time model, controller state; before the first pass the planner's stage, with its
// share done and ETA where it tells one), JSON events with the same fields (--json), or
// nothing (--quiet). Controller messages, errors and the final summary go through the
// StreamReporter that `send` uses. Also notes when the first block left and when the first
// cutting block left, for the time-to-first-block figure.

#include "job/job_pipeline.hpp"
#include "stream_reporter.hpp"

#include <chrono>
#include <optional>

namespace subfeed::cli {

class JobReporter final : public drivers::StreamObserver {
public:
  // `acks`: the controller acknowledges lines (GRBL); without, a block counts once sent.
  // `speed`: the simulated machine runs this many times faster than real time.
  JobReporter(Logger& log, bool json, job::JobPipeline& job, bool acks, double speed);

  void connected(const drivers::ControllerInfo& info) override { inner_.connected(info); }
  void progress(const drivers::StreamProgress& progress) override;
  void message(std::string_view line) override;
  void line_error(const drivers::LineError& error) override;
  void phase(std::string_view name) override { inner_.phase(name); }
  void line_sent(long line, long bytes) override;
  void line_answered(long line, int error_code) override;

  // After the stream: its summary or error, below the progress line.
  void finished(const drivers::StreamSummary& summary, std::optional<int> baud,
                int bits_per_character);
  void failed(const Error& error);
  [[nodiscard]] std::optional<double> first_block_s() const { return first_block_s_; }
  // Seconds from start until the first line that moves an axis was sent.
  [[nodiscard]] std::optional<double> first_move_s() const { return first_move_s_; }
  // Seconds from start to the end of the stream (once finished() was called).
  [[nodiscard]] double streamed_s() const { return streamed_s_; }

private:
  void end_line();

  StreamReporter inner_;
  job::JobPipeline& job_;
  bool json_, terminal_, acks_;
  bool shown_ = false; // a progress line is on the terminal
  double speed_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_update_{};
  // The planner's stage last shown and when it was first seen, for that stage's ETA.
  std::optional<geometry::PlanStage> stage_seen_;
  std::chrono::steady_clock::time_point stage_seen_at_{};
  std::optional<double> first_block_s_;
  std::optional<double> first_move_s_;
  double streamed_s_ = 0.0;
  long done_line_ = 0;
  long sent_ = 0, done_ = 0;
};

} // namespace subfeed::cli
