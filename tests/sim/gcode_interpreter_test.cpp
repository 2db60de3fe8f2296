#include "sim/gcode_interpreter.hpp"

#include <catch2/catch.hpp>

using subfeed::sim::AxisArray;
using subfeed::sim::GcodeInterpreter;

TEST_CASE("sim interpreter: absolute and incremental targets, in the work offset") {
  GcodeInterpreter g(3, AxisArray{100.0, 50.0, -10.0, 0, 0, 0});
  const AxisArray home{};
  auto r = g.execute("G0X10Y20", home);
  REQUIRE(r.error == 0);
  CHECK(r.move.present);
  CHECK(r.move.rapid);
  CHECK(r.move.target == AxisArray{110.0, 70.0, 0.0, 0, 0, 0}); // Z not named: stays
  r = g.execute("G91G1X-5F600", r.move.target);
  REQUIRE(r.error == 0);
  CHECK_FALSE(r.move.rapid);
  CHECK(r.move.target == AxisArray{105.0, 70.0, 0.0, 0, 0, 0});
  CHECK(r.move.feed_mm_min == 600.0);
  r = g.execute("X1", r.move.target); // G91 and G1 stay in force, and the feed too
  CHECK(r.move.target[0] == 106.0);
  CHECK(r.move.feed_mm_min == 600.0);
}

TEST_CASE("sim interpreter: inches scale lengths and feeds, not angles") {
  GcodeInterpreter g(4);
  const auto r = g.execute("G20G1X1A10F10", AxisArray{});
  REQUIRE(r.error == 0);
  CHECK(r.move.target[0] == Approx(25.4));
  CHECK(r.move.target[3] == 10.0);
  CHECK(r.move.feed_mm_min == Approx(254.0));
}

TEST_CASE("sim interpreter: inverse time gives the block's duration and needs F each block") {
  GcodeInterpreter g(5);
  auto r = g.execute("G93G1X10A5F20", AxisArray{});
  REQUIRE(r.error == 0);
  CHECK(r.move.inverse_time_min == Approx(0.05));
  CHECK(g.execute("X20", r.move.target).error == 22); // no F in a G93 block
  r = g.execute("G94G1X30F1000", r.move.target);
  REQUIRE(r.error == 0);
  CHECK(r.move.inverse_time_min == 0.0);
  CHECK(r.move.feed_mm_min == 1000.0);
}

TEST_CASE("sim interpreter: GRBL's error codes, and no modal change from a refused line") {
  GcodeInterpreter g(3);
  const AxisArray at{};
  CHECK(g.execute("G1X1", at).error == 22);    // a feed move before any feed
  CHECK(g.execute("1X", at).error == 1);       // a number where a letter should be
  CHECK(g.execute("X", at).error == 2);        // a letter without a number
  CHECK(g.execute("G0G1X1", at).error == 21);  // two motion words
  CHECK(g.execute("M3.5", at).error == 23);    // an M code that is not an integer
  CHECK(g.execute("X1X2", at).error == 25);    // a word repeated
  CHECK(g.execute("A10", at).error == 20);     // an axis this machine lacks
  CHECK(g.execute("G43.4", at).error == 20);   // not GRBL
  CHECK(g.execute("G91G5X1", at).error == 20); // refused whole: G91 not taken
  const auto r = g.execute("G0X1", at);
  CHECK(r.move.target[0] == 1.0); // still absolute
}

TEST_CASE("sim interpreter: EEPROM writes and dwells are told apart from moves") {
  GcodeInterpreter g(3);
  const AxisArray at{};
  auto r = g.execute("G10L2P1X5", at);
  CHECK(r.writes_eeprom);
  CHECK_FALSE(r.move.present);
  CHECK(g.execute("G28.1", at).writes_eeprom);
  CHECK_FALSE(g.execute("G0X1", at).writes_eeprom);
  r = g.execute("G4P1.5", at);
  CHECK(r.dwell_s == 1.5);
  CHECK_FALSE(r.move.present);
}

TEST_CASE("sim interpreter: reset returns to power-up modes") {
  GcodeInterpreter g(3);
  REQUIRE(g.execute("G91G20G1F5", AxisArray{}).error == 0);
  g.reset();
  const auto r = g.execute("X2", AxisArray{});
  CHECK(r.move.rapid);            // G0
  CHECK(r.move.target[0] == 2.0); // G90, mm
}
