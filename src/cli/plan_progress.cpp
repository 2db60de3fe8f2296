#include "plan_progress.hpp"

#include "progress_text.hpp"

#include <cstdio>
#include <fmt/format.h>

namespace subfeed::cli {

PlanProgress::PlanProgress(bool enabled)
    : enabled_(enabled), start_(std::chrono::steady_clock::now()), last_shown_(start_) {}

void PlanProgress::show(const std::string& text, bool always) {
  if (!enabled_) {
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!always && now - last_shown_ < std::chrono::milliseconds(100)) {
    return;
  }
  last_shown_ = now;
  shown_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[Kplanning %s  %s", clock_text(elapsed).c_str(), text.c_str());
  std::fflush(stderr);
}

geometry::PlanObserver PlanProgress::observer() {
  return {[this](geometry::PlanStage s) { stage(s); },
          [this](int solve_number, int most) { solve(solve_number, most); },
          [this](double done) { share(done); }};
}

void PlanProgress::stage(geometry::PlanStage stage) {
  stage_name_ = geometry::stage_name(stage);
  stage_start_ = std::chrono::steady_clock::now();
  stage_share_shown_ = false;
  show(stage_name_, true);
}

void PlanProgress::share(double done) {
  const double spent =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
  show(fmt::format("{} {} {:5.1f}%  ETA {}", stage_name_, progress_bar(done), 100.0 * done,
                   eta_text(spent, done)),
       !stage_share_shown_); // the first always: a short stage shows its bar too
  stage_share_shown_ = true;
}

void PlanProgress::solve(int solve, int most) {
  const auto now = std::chrono::steady_clock::now();
  if (solve <= 1) {
    solves_start_ = now;
  }
  const double spent = std::chrono::duration<double>(now - solves_start_).count();
  const std::string eta =
      solve > 1 ? "at most " + clock_text(spent / (solve - 1) * (most - solve + 1)) : "--:--";
  show(fmt::format("deformation solve {} of at most {}  ETA {}", solve, most, eta), solve == 1);
}

void PlanProgress::plane(long plane, long planes) {
  const auto now = std::chrono::steady_clock::now();
  if (!slicing_) {
    slicing_ = true;
    slicing_start_ = now;
  }
  const double done = planes > 0 ? static_cast<double>(plane) / static_cast<double>(planes) : 0.0;
  const double spent = std::chrono::duration<double>(now - slicing_start_).count();
  show(fmt::format("{} {:5.1f}%  plane {} of {}  ETA {}", progress_bar(done), 100.0 * done, plane,
                   planes, eta_text(spent, done)),
       plane == 0);
}

PlanProgress::~PlanProgress() {
  finish();
}

void PlanProgress::finish() {
  if (shown_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
  }
}

} // namespace subfeed::cli
