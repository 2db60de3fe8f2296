#include "post/rotary_tracker.hpp"

#include "post/kinematics.hpp"
#include "post/machine_config.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace subfeed;
using namespace subfeed::post;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

MachineConfig trunnion() {
  // A from -100 to 50 deg, C unlimited; a_direction = c_direction = 1.
  return load_machine_config(SUBFEED_SOURCE_DIR "/configs/grblhal-xyzac-trt.toml").value();
}

// A tool tilted `tilt_deg` from +Z, leaning toward the direction `toward_deg` from +X.
cl::ClPose leaning(double tilt_deg, double toward_deg, long line = 1) {
  cl::ClPose p;
  p.tip = {10.0, -5.0, 2.0};
  p.axis = {std::sin(tilt_deg * deg) * std::cos(toward_deg * deg),
            std::sin(tilt_deg * deg) * std::sin(toward_deg * deg), std::cos(tilt_deg * deg)};
  p.line = line;
  return p;
}

// In degrees; atan2 of the cross and dot products stays exact for tiny angles, where acos
// of the dot product cannot resolve below about 1e-6 deg.
double angle_between(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
               cz = a[0] * b[1] - a[1] * b[0];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) / deg;
}

} // namespace

TEST_CASE("rotary tracker: every step carries the tool along its axis, inside the limits, "
          "turning C no more than the tool turns") {
  const auto machine = trunnion();
  const auto kinematics = make_kinematics(machine);
  for (const double tilt : {5.0, 40.0, 85.0}) {
    RotaryTracker tracker(*kinematics, machine);
    const auto first = leaning(tilt, 0.0);
    tracker.start_at(tracker.prefer(tracker.start_candidates(first).value()));
    double last_c = tracker.current()[5];
    for (double toward = 5.0; toward <= 720.0; toward += 5.0) {
      const auto pose = leaning(tilt, toward);
      const auto step = tracker.step(pose);
      REQUIRE(step);
      CHECK_FALSE(step->reposition);
      const auto reached = kinematics->forward(step->joints);
      CHECK(angle_between(reached.axis, pose.axis) < 1e-7);
      for (std::size_t i = 0; i < 3; ++i) {
        CHECK(reached.tip[i] == Approx(pose.tip[i]).margin(1e-9));
      }
      CHECK(step->joints[3] >= -100.0);
      CHECK(step->joints[3] <= 50.0);
      CHECK(std::abs(step->joints[5] - last_c) == Approx(5.0).margin(1e-6)); // C unwinds, no jump
      last_c = step->joints[5];
    }
  }
}

TEST_CASE("rotary tracker: the limits choose the branch") {
  const auto machine = trunnion();
  const auto kinematics = make_kinematics(machine);
  RotaryTracker tracker(*kinematics, machine);
  // Leaning 60 deg toward -Y is A = 60, C = 0 (over the A limit of 50) or A = -60, C = 180.
  const auto candidates = tracker.start_candidates(leaning(60.0, -90.0)).value();
  REQUIRE_FALSE(candidates.empty());
  for (const auto& j : candidates) {
    CHECK(j[3] == Approx(-60.0));
    CHECK(std::fmod(std::abs(j[5]), 360.0) == Approx(180.0));
  }
}

TEST_CASE("rotary tracker: a path over the pole tips the table through it, C held") {
  const auto machine = trunnion();
  const auto kinematics = make_kinematics(machine);
  RotaryTracker tracker(*kinematics, machine);
  tracker.start_at(tracker.prefer(tracker.start_candidates(leaning(30.0, 90.0)).value()));
  const double c = tracker.current()[5];
  const double a = tracker.current()[3];
  // From 30 deg toward +Y through vertical to 30 deg toward -Y, in the YZ plane.
  for (int tilt = 29; tilt >= -30; --tilt) {
    const auto step = tracker.step(leaning(std::abs(tilt), tilt >= 0 ? 90.0 : -90.0));
    REQUIRE(step);
    CHECK_FALSE(step->reposition);
    CHECK(step->joints[5] == Approx(c).margin(1e-9));
  }
  CHECK(tracker.current()[3] == Approx(-a)); // the tilt changed sign, through 0
}

TEST_CASE("rotary tracker: a pose no solution reaches is an error naming its CL line") {
  const auto machine = trunnion();
  const auto kinematics = make_kinematics(machine);
  RotaryTracker tracker(*kinematics, machine);
  tracker.start_at(tracker.prefer(tracker.start_candidates(leaning(10.0, 0.0)).value()));
  // 120 deg from vertical: A = +-120, outside -100..50 either way.
  const auto step = tracker.step(leaning(120.0, 0.0, 42));
  REQUIRE_FALSE(step);
  CHECK(step.error().where.line == 42);
  CHECK(step.error().code == ErrorCode::bad_input);
  CHECK_FALSE(tracker.start_candidates(leaning(120.0, 0.0, 43)));
}
