#pragma once
// `plan`'s progress on a terminal: one line on stderr, rewritten at most ten times a second,
// through every stage of the planner as it starts (geometry/plan_stages.hpp) with its share
// done and an ETA where the stage tells one (meshing, the gate's mesh, reach), each
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
  // The share of the current stage done (0..1): a bar and an ETA from its rate so far.
  void share(double done);
  void solve(int solve, int most);
  void plane(long plane, long planes);
  // Erases the line before the summary.
  void finish();

private:
  void show(const std::string& text, bool always);

  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_shown_, slicing_start_, solves_start_,
      stage_start_;
  std::string stage_name_;
  bool slicing_ = false;
  bool stage_share_shown_ = false;
  bool shown_ = false; // a line is on the terminal
};

} // namespace subfeed::cli
