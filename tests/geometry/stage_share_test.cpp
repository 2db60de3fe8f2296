// A stage's share done, as a long plan's progress line hears it.

#include "geometry/stage_share.hpp"

#include <catch2/catch.hpp>
#include <thread>
#include <vector>

using namespace std::chrono_literals;
using subfeed::geometry::StageShare;

TEST_CASE("a stage's share counts its steps in turn and is told at most ten times a second") {
  std::vector<double> told;
  StageShare share([&](double done) { told.push_back(done); }, 3);
  for (int step = 0; step < 3; ++step) {
    for (std::size_t i = 0; i < 64; ++i) {
      share.tell(0, i, 64);
      share.tell(64, 64 + i, 128); // another thread's share: never told
      if (i % 16 == 15) {
        std::this_thread::sleep_for(110ms); // past the throttle before the next check
      }
    }
    share.next_step();
  }
  // Checked every 16 items of the first share (the other share's calls are not counted): after
  // items 16, 32, 48 and 64 of each step's 64.
  std::vector<double> expected;
  for (int step = 0; step < 3; ++step) {
    for (const double in_step : {16.0, 32.0, 48.0, 64.0}) {
      expected.push_back((step + in_step / 64.0) / 3.0);
    }
  }
  REQUIRE(told.size() == expected.size());
  for (std::size_t k = 0; k < told.size(); ++k) {
    CHECK(told[k] == Approx(expected[k]));
  }
}
