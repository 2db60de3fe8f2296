#include "post/config_kind.hpp"
#include "post/tool_table.hpp"

#include <catch2/catch.hpp>

using subfeed::post::parse_tool_table;

namespace {

// Line numbers are part of the expected messages: keep the layout.
const std::string two_tools = R"([slim]
cutter = "ball"
diameter = 2.0
shank = 4
stickout = 20.0
holder = [[20.0, 32.0, 30.0], [50, 20]]
[plain]
cutter = "ball"
diameter = 6
)";

std::string with_replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string table_error(const std::string& text) {
  const auto table = parse_tool_table(text, "tools.toml");
  REQUIRE_FALSE(table);
  return table.error().describe();
}

} // namespace

TEST_CASE("tool table: every tool by name, its sizes, cones and cylinders, unset sizes left "
          "to the defaults") {
  const auto table = parse_tool_table(two_tools, "tools.toml");
  REQUIRE(table);
  REQUIRE(table->tools.size() == 2);
  const auto* slim = table->find("slim");
  REQUIRE(slim != nullptr);
  CHECK(slim->line == 1);
  CHECK(slim->diameter == 2.0);
  CHECK_FALSE(slim->flute);
  CHECK(slim->shank == 4.0);
  CHECK(slim->stickout == 20.0);
  REQUIRE(slim->holder.size() == 2);
  CHECK(slim->holder[0].bottom_diameter == 20.0);
  CHECK(slim->holder[0].top_diameter == 32.0);
  CHECK(slim->holder[0].length == 30.0);
  CHECK(slim->holder[1].bottom_diameter == 50.0);
  CHECK(slim->holder[1].top_diameter == 50.0);
  CHECK(slim->holder[1].length == 20.0);
  const auto* plain = table->find("plain");
  REQUIRE(plain != nullptr);
  CHECK(plain->line == 7);
  CHECK(plain->holder.empty());
  CHECK_FALSE(plain->stickout);
  CHECK(table->find("other") == nullptr);
}

TEST_CASE("tool table: each mistake is one error naming the line and the dotted key") {
  CHECK(table_error(with_replaced(two_tools, "shank = 4", "shnk = 4")) ==
        "tools.toml:4: slim.shnk: unknown key");
  CHECK(table_error(with_replaced(two_tools, "diameter = 6", "diameter = 0")) ==
        "tools.toml:9: plain.diameter: 0 mm is outside 0 (excluded) .. 10000 mm");
  CHECK(table_error(with_replaced(two_tools, "diameter = 6\n", "")) ==
        "tools.toml:7: plain.diameter: missing required key (a number)");
  CHECK(table_error(with_replaced(two_tools, "cutter = \"ball\"\ndiameter = 6",
                                  "cutter = \"flat\"\ndiameter = 6")) ==
        "tools.toml:8: plain.cutter: 'flat' is not one of ball");
  CHECK(table_error(with_replaced(two_tools, "[50, 20]", "[50, 20, 1, 2]")) ==
        "tools.toml:6: slim.holder: expected stages [D, L] or [D1, D2, L], bottom first, each "
        "size above 0 and at most 10000 mm");
  CHECK(table_error(with_replaced(two_tools, "[50, 20]", "[50, -20]"))
            .starts_with("tools.toml:6: slim.holder: "));
  CHECK(table_error(
            with_replaced(two_tools, "holder = [[20.0, 32.0, 30.0], [50, 20]]", "holder = 32")) ==
        "tools.toml:6: slim.holder: expected an array of arrays of numbers, got an integer");
  CHECK(table_error(with_replaced(two_tools, "stickout = 20.0", "stickout = \"20\"")) ==
        "tools.toml:5: slim.stickout: expected a number, got a string");
  CHECK(table_error("name = 3\n") == "tools.toml:1: name: expected a table, got an integer");
  CHECK(table_error("[\"ball:6\"]\ncutter = \"ball\"\ndiameter = 6\n") ==
        "tools.toml:1: ball:6: a tool's name may not hold ':' (--tool would read it as a cutter, "
        "ball:D)");
  CHECK(table_error("# nothing\n") == "tools.toml: no tools: expected one [NAME] table per tool");
  CHECK(table_error("[a\n").starts_with("tools.toml:1: TOML syntax: "));
}

TEST_CASE("the shipped tool table loads, and is told from the machine configs by its content") {
  const std::string dir = std::string(SUBFEED_SOURCE_DIR) + "/configs/";
  const auto table = subfeed::post::load_tool_table(dir + "tools.toml");
  REQUIRE(table);
  CHECK(table->tools.size() >= 3);
  CHECK(table->find("ball6-er32") != nullptr);
  CHECK(subfeed::post::config_kind(dir + "tools.toml") == subfeed::post::ConfigKind::tool_table);
  CHECK(subfeed::post::config_kind(dir + "grbl-router-3axis.toml") ==
        subfeed::post::ConfigKind::machine);
  const auto missing = subfeed::post::load_tool_table("/nonexistent/tools.toml");
  REQUIRE_FALSE(missing);
  CHECK(missing.error().describe() == "/nonexistent/tools.toml: cannot open tool table");
}
