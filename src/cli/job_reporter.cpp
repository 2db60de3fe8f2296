#include "job_reporter.hpp"

#include "progress_text.hpp"

#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

JobReporter::JobReporter(Logger& log, bool json, JobPipeline& job, bool acks, double speed)
    : inner_(log, json), job_(job), json_(json),
      terminal_(!json && log.verbosity() != Verbosity::quiet && ::isatty(STDERR_FILENO) != 0),
      acks_(acks), speed_(speed), start_(std::chrono::steady_clock::now()) {}

void JobReporter::line_sent(long line, long /*bytes*/) {
  ++sent_;
  const double now =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (!first_block_s_) {
    first_block_s_ = now;
  }
  const long first_move = job_.first_motion_line();
  if (!first_move_s_ && first_move > 0 && line >= first_move) {
    first_move_s_ = now;
  }
  if (!acks_ && line > 0) {
    done_line_ = line;
    ++done_;
  }
}

void JobReporter::line_answered(long line, int /*error_code*/) {
  if (line > 0) {
    done_line_ = line;
    ++done_;
  }
}

void JobReporter::end_line() {
  if (shown_) {
    std::fputs("\n", stderr);
    shown_ = false;
  }
}

void JobReporter::message(std::string_view line) {
  end_line();
  inner_.message(line);
}

void JobReporter::line_error(const drivers::LineError& error) {
  end_line();
  inner_.line_error(error);
}

void JobReporter::finished(const drivers::StreamSummary& summary, std::optional<int> baud,
                           int bits_per_character) {
  streamed_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  end_line();
  inner_.finished(summary, baud, bits_per_character);
}

void JobReporter::failed(const Error& error) {
  end_line();
  inner_.failed(error);
}

void JobReporter::progress(const drivers::StreamProgress& p) {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_update_ < std::chrono::milliseconds(json_ ? 500 : 200)) {
    return;
  }
  last_update_ = now;
  const JobProgress j = job_.progress(done_line_);
  const double percent = j.cut_total_mm > 0.0 ? 100.0 * j.cut_done_mm / j.cut_total_mm : 0.0;
  const double eta_s = (j.minutes_total - j.minutes_done) * 60.0 / speed_;
  const std::string state = state_text(p);
  // Before the first pass the planner's own stage is what is happening.
  std::string stage;
  if (!j.planned && j.passes == 0 && j.stage) {
    if (j.stage != stage_seen_) {
      stage_seen_ = j.stage;
      stage_seen_at_ = now;
    }
    stage = std::string(geometry::stage_name(*j.stage));
    if (*j.stage == geometry::PlanStage::deformation && j.solve > 0) {
      stage += fmt::format(" {} of at most {}", j.solve, j.most_solves);
    } else if (j.stage_share >= 0.0) {
      const double spent = std::chrono::duration<double>(now - stage_seen_at_).count();
      stage +=
          fmt::format(" {:.0f}% ETA {}", 100.0 * j.stage_share, eta_text(spent, j.stage_share));
    }
  }
  if (json_) {
    std::printf("{\"event\":\"progress\",\"passes\":%ld,\"planned\":%s,\"posted\":%ld,"
                "\"sent\":%ld,\"done\":%ld,\"cut_percent\":%.2f,\"eta_s\":%.1f,"
                "\"elapsed_s\":%.2f,\"state\":\"%s\"%s}\n",
                j.passes, j.planned ? "true" : "false", j.lines_posted, sent_, done_, percent,
                eta_s, p.elapsed_s, json_escape(state).c_str(),
                stage.empty() ? "" : (",\"stage\":\"" + json_escape(stage) + "\"").c_str());
    std::fflush(stdout);
  } else if (terminal_ && !stage.empty()) {
    std::fprintf(stderr, "\rplanning: %s  %-8s\x1b[K", stage.c_str(), state.c_str());
    shown_ = true;
  } else if (terminal_) {
    std::fprintf(stderr, "\r%s %5.1f%% cut  passes %ld%s  posted %ld  %s %ld  ETA %s%s  %-8s\x1b[K",
                 progress_bar(percent / 100.0).c_str(), percent, j.passes, j.planned ? "" : "+",
                 j.lines_posted, acks_ ? "acked" : "sent", done_, clock_text(eta_s).c_str(),
                 j.planned ? "" : "~", state.c_str());
    shown_ = true;
  }
}

} // namespace subfeed::cli
