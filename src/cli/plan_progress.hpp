#pragma once
// `plan`'s progress on a terminal: one line on stderr, rewritten at most ten times a second,
// through every stage of the planner as it starts (geometry/plan_stages.hpp), each
// deformation solve with the longest the rest can take (solves stop early once the spacing
// holds), then the planes cut with the share done and an ETA from the rate so far. Disabled, it
// writes nothing. The line is erased by finish() or, on an early return, by the destructor, so an
// error line that follows starts clean.

#include "geometry/plan_stages.hpp"

#include <chrono>
#include <string>

namespace subfeed::cli {

class PlanProgress {
public:
  explicit PlanProgress(bool enabled);
  ~PlanProgress();
  PlanProgress(const PlanProgress&) = delete;
  PlanProgress& operator=(const PlanProgress&) = delete;

  // The planner's observer, reporting to this line.
  [[nodiscard]] geometry::PlanObserver observer();
  void stage(geometry::PlanStage stage);
  void solve(int solve, int most);
  void plane(long plane, long planes);
  // Erases the line before the summary.
  void finish();

private:
  void show(const std::string& text, bool always);

  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_shown_, slicing_start_, solves_start_;
  bool slicing_ = false;
  bool shown_ = false; // a line is on the terminal
};

} // namespace subfeed::cli
