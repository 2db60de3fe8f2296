#pragma once
// The simulated machine's planner queue and motion-time model. A block takes its length
// over its feed (or its inverse-time duration), plus an acceleration ramp v/(2a) whenever
// the machine starts from rest and another whenever it has to stop because the queue ran
// dry. That makes the cost of a starved planner visible, which is what a sender's streaming
// speed is judged by. Lengths combine all axes as GRBL does (deg count as mm).

#include "sim/gcode_interpreter.hpp"

#include <cstddef>
#include <deque>

namespace subfeed::sim {

struct MotionModel {
  double acceleration_mm_s2 = 500.0;
  double rapid_mm_min = 5000.0;
  double speed = 1.0; // time scale: 10 runs the machine ten times faster than real time
};

class MotionPlanner {
public:
  MotionPlanner(int capacity, MotionModel model) : capacity_(capacity), model_(model) {}

  [[nodiscard]] bool full() const { return static_cast<int>(queue_.size()) >= capacity_; }
  [[nodiscard]] int free_blocks() const { return capacity_ - static_cast<int>(queue_.size()); }
  [[nodiscard]] bool empty() const { return queue_.empty(); }

  void push(const SimMove& move);
  void push_dwell(double seconds);

  // Runs the machine for `real_seconds` (scaled by the model's speed); returns how many
  // blocks finished. While `holding`, nothing moves.
  std::size_t advance(double real_seconds, bool holding);

  [[nodiscard]] const AxisArray& position() const { return position_; }
  // Where the next pushed block starts.
  [[nodiscard]] const AxisArray& planned_end() const { return planned_end_; }
  [[nodiscard]] double current_feed_mm_min() const;
  [[nodiscard]] std::size_t starvations() const { return starvations_; }
  // Seconds a feed hold takes to stop from the current feed.
  [[nodiscard]] double stop_seconds() const;

  void clear(); // reset: queue dropped, position kept
  void set_position(const AxisArray& p);

private:
  struct Block {
    AxisArray start{};
    AxisArray target{};
    double duration_s = 0.0; // machine time, ramps included
    double feed_mm_min = 0.0;
    double elapsed_s = 0.0;
  };

  int capacity_;
  MotionModel model_;
  std::deque<Block> queue_;
  AxisArray position_{};
  AxisArray planned_end_{};
  bool at_rest_ = true;
  std::size_t starvations_ = 0;
};

} // namespace subfeed::sim
