#include "sim/motion_planner.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::sim {

namespace {

double length(const AxisArray& a, const AxisArray& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum += (b[i] - a[i]) * (b[i] - a[i]);
  }
  return std::sqrt(sum);
}

} // namespace

void MotionPlanner::push(const SimMove& move) {
  Block block;
  block.start = planned_end_;
  block.target = move.target;
  const double distance = length(block.start, block.target);
  if (move.inverse_time_min > 0.0) {
    block.duration_s = move.inverse_time_min * 60.0;
    block.feed_mm_min = block.duration_s > 0.0 ? distance / block.duration_s * 60.0 : 0.0;
  } else {
    block.feed_mm_min = move.rapid ? model_.rapid_mm_min : move.feed_mm_min;
    block.duration_s = block.feed_mm_min > 0.0 ? distance / block.feed_mm_min * 60.0 : 0.0;
  }
  planned_end_ = block.target;
  queue_.push_back(block);
}

void MotionPlanner::push_dwell(double seconds) {
  Block block;
  block.start = block.target = planned_end_;
  block.duration_s = seconds;
  queue_.push_back(block);
}

double MotionPlanner::current_feed_mm_min() const {
  return queue_.empty() || at_rest_ ? 0.0 : queue_.front().feed_mm_min;
}

double MotionPlanner::stop_seconds() const {
  return current_feed_mm_min() / 60.0 / model_.acceleration_mm_s2;
}

std::size_t MotionPlanner::advance(double real_seconds, bool holding) {
  if (holding) {
    at_rest_ = true; // a held machine accelerates again when resumed
    return 0;
  }
  double budget = real_seconds * model_.speed;
  std::size_t finished = 0;
  while (budget > 0.0 && !queue_.empty()) {
    Block& block = queue_.front();
    if (at_rest_) {
      const double v = block.feed_mm_min / 60.0;
      block.duration_s += v / (2.0 * model_.acceleration_mm_s2);
      at_rest_ = false;
    }
    const double step = std::min(budget, block.duration_s - block.elapsed_s);
    block.elapsed_s += step;
    budget -= step;
    const double t = block.duration_s > 0.0 ? block.elapsed_s / block.duration_s : 1.0;
    for (std::size_t i = 0; i < position_.size(); ++i) {
      position_[i] = block.start[i] + (block.target[i] - block.start[i]) * t;
    }
    if (block.elapsed_s >= block.duration_s) {
      position_ = block.target;
      const double v = block.feed_mm_min / 60.0;
      queue_.pop_front();
      ++finished;
      if (queue_.empty()) {
        // Starved or done: the machine has to brake to a stop.
        budget -= v / (2.0 * model_.acceleration_mm_s2);
        at_rest_ = true;
        ++starvations_;
      }
    }
  }
  return finished;
}

void MotionPlanner::clear() {
  queue_.clear();
  planned_end_ = position_;
  at_rest_ = true;
}

void MotionPlanner::set_position(const AxisArray& p) {
  position_ = p;
  planned_end_ = p;
}

} // namespace subfeed::sim
