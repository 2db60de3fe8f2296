#pragma once
// A stage's progress told as it goes, for an ETA on a long plan.

#include <chrono>
#include <cstddef>
#include <functional>
#include <utility>

namespace subfeed::geometry {

// Counts a stage's work, in `steps` equal steps, toward PlanObserver::share, telling it at
// most ten times a second. Work split across threads (split_work.hpp) is counted by its
// first share only, which runs on the caller's thread and stands for the rest: tell() does
// nothing for items of a share that does not begin at 0.
class StageShare {
public:
  explicit StageShare(std::function<void(double)> report, int steps = 1)
      : report_(std::move(report)), steps_(steps > 0 ? steps : 1) {}

  // Item `i` of the share [begin, end) of the current step has been done.
  void tell(std::size_t begin, std::size_t i, std::size_t end) {
    if (!report_ || begin != 0 || end == 0 || ++calls_ % 16 != 0) {
      return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - told_at_ < std::chrono::milliseconds(100)) {
      return;
    }
    told_at_ = now;
    const double in_step = static_cast<double>(i + 1) / static_cast<double>(end);
    report_((static_cast<double>(step_) + in_step) / static_cast<double>(steps_));
  }
  void next_step() { ++step_; }

private:
  std::function<void(double)> report_;
  int steps_;
  int step_ = 0;
  long calls_ = 0;
  std::chrono::steady_clock::time_point told_at_{};
};

} // namespace subfeed::geometry
