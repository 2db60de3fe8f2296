#include "job/motion_time.hpp"

#include "post/machine_config.hpp"

#include <catch2/catch.hpp>

using namespace subfeed;

namespace {

post::MachineConfig router() {
  return post::load_machine_config(SUBFEED_SOURCE_DIR "/configs/grbl-router-3axis.toml").value();
}

post::MotionBlock feed_to(double x, double y, double feed) {
  post::MotionBlock b;
  b.motion = post::Motion::linear;
  b.axes[0] = x;
  b.axes[1] = y;
  b.feed = feed;
  return b;
}

constexpr double acceleration = 500.0 * 3600.0; // mm/min^2, the model's default 500 mm/s^2

} // namespace

TEST_CASE("motion time: a feed move is its length over F, with a ramp from rest") {
  const auto machine = router();
  job::MotionTimeModel model(machine);
  // From rest: 100 mm at 1000 mm/min, plus the ramp up and down (v / a).
  CHECK(model.add(feed_to(100, 0, 1000)) == Approx(0.1 + 1000.0 / acceleration));
  // Going on the same way at speed: no ramp.
  CHECK(model.add(feed_to(200, 0, 1000)) == Approx(0.1));
  // A turn of 90 degrees keeps going; lengths combine X and Y.
  CHECK(model.add(feed_to(230, 40, 1000)) == Approx(0.05));
  // Reversing stops the machine: a ramp again.
  CHECK(model.add(feed_to(200, 0, 1000)) == Approx(0.05 + 1000.0 / acceleration));
  // A block that moves nothing takes no time.
  CHECK(model.add(feed_to(200, 0, 1000)) == 0.0);
}

TEST_CASE("motion time: inverse time is 1/F minutes, rapids run at the slowest axis's max") {
  const auto machine = router();
  job::MotionTimeModel model(machine);
  REQUIRE(model.add(feed_to(10, 0, 1000)) > 0.0);
  post::MotionBlock g93 = feed_to(20, 0, 20.0);
  g93.feed_mode = post::FeedMode::inverse_time;
  CHECK(model.add(g93) == Approx(0.05));
  // X 500 mm at 5000 mm/min and Z 150 mm at 1500 mm/min both take 0.1 min; the rapid ends
  // at rest and starts from a stop.
  post::MotionBlock rapid;
  rapid.motion = post::Motion::rapid;
  rapid.axes[0] = 520.0;
  rapid.axes[2] = 150.0;
  const double length = std::sqrt(500.0 * 500.0 + 150.0 * 150.0);
  CHECK(model.add(rapid) == Approx(0.1 + (length / 0.1) / acceleration));
}
