#include "drivers/line_ranges.hpp"

#include <catch2/catch.hpp>

using subfeed::drivers::describe_lines;

TEST_CASE("file lines are told as runs, sorted, each once") {
  CHECK(describe_lines({}) == "");
  CHECK(describe_lines({41}) == "line 41");
  CHECK(describe_lines({41, 42, 43}) == "lines 41-43");
  CHECK(describe_lines({47, 41, 42, 43, 50, 51, 52}) == "lines 41-43, 47, 50-52");
  CHECK(describe_lines({5, 5, 7}) == "lines 5, 7");
  CHECK(describe_lines({9, 8}) == "lines 8-9");
}
