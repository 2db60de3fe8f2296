#include "job/motion_time.hpp"

#include <algorithm>
#include <cmath>

namespace subfeed::job {

MotionTimeModel::MotionTimeModel(const post::MachineConfig& machine, double acceleration_mm_s2)
    : machine_(&machine), acceleration_(acceleration_mm_s2 * 3600.0) {}

double MotionTimeModel::add(const post::MotionBlock& block) {
  std::array<double, 6> delta{};
  double length = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    if (block.axes[i]) {
      delta[i] = *block.axes[i] - at_[i];
      at_[i] = *block.axes[i];
    }
    length += delta[i] * delta[i];
  }
  length = std::sqrt(length);
  if (length == 0.0) {
    return 0.0;
  }
  double minutes = 0.0;
  double speed = 0.0; // mm/min
  if (block.motion == post::Motion::rapid) {
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& axis = machine_->axes[i];
      if (delta[i] != 0.0 && axis && axis->max_feed > 0.0) {
        minutes = std::max(minutes, std::abs(delta[i]) / axis->max_feed);
      }
    }
    speed = minutes > 0.0 ? length / minutes : 0.0;
  } else {
    minutes = block.feed_mode == post::FeedMode::inverse_time
                  ? (block.feed > 0.0 ? 1.0 / block.feed : 0.0)
                  : (block.feed > 0.0 ? length / block.feed : 0.0);
    speed = minutes > 0.0 ? length / minutes : 0.0;
  }
  double turn = 0.0; // cosine of the angle to the previous direction
  for (std::size_t i = 0; i < 6; ++i) {
    turn += last_direction_[i] * delta[i] / length;
    last_direction_[i] = delta[i] / length;
  }
  const bool stops = block.motion == post::Motion::rapid || turn < 0.0;
  if (at_rest_ || stops) {
    minutes += speed / acceleration_; // up to speed here, and down to rest before
  }
  at_rest_ = block.motion == post::Motion::rapid;
  return minutes;
}

} // namespace subfeed::job
