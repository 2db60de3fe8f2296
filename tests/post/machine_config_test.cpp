#include "post/config_kind.hpp"
#include "post/machine_config.hpp"

#include <catch2/catch.hpp>
#include <filesystem>

using subfeed::post::KinematicsType;
using subfeed::post::parse_machine_config;

namespace {

// A complete, valid xyzac-trt config; tests replace one line at a time. Line numbers are
// part of the expected messages, so keep the layout.
const std::string trt = R"([machine]
name = "test trunnion"
kinematics = "xyzac-trt"
[kinematics]
pivot = [1.0, 2.0, 3.0]
y_offset = 4.0
z_offset = 5.0
a_direction = -1
c_direction = 1
[axes.x]
min = -100.0
max = 100.0
max_feed = 3000
[axes.y]
min = -100.0
max = 100.0
max_feed = 3000
[axes.z]
min = -100.0
max = 0.0
max_feed = 1000
[axes.a]
min = -100.0
max = 50.0
max_feed = 3600
[axes.c]
cyclic = true
max_feed = 7200
[controller]
protocol = "grbl"
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

void expect_error(const std::string& text, const std::string& description) {
  const auto config = parse_machine_config(text, "m.toml");
  REQUIRE_FALSE(config);
  CHECK(config.error().code == subfeed::ErrorCode::bad_input);
  CHECK(config.error().describe() == description);
}

} // namespace

TEST_CASE("a complete config is read with its defaults") {
  const auto config = parse_machine_config(trt, "m.toml");
  REQUIRE(config);
  CHECK(config->name == "test trunnion");
  CHECK(config->kinematics == KinematicsType::xyzac_trt);
  REQUIRE(config->rotary);
  CHECK(config->rotary->pivot == std::array<double, 3>{1, 2, 3});
  CHECK(config->rotary->tilt_direction == -1);
  CHECK(config->rotary->tool_length == 0.0);
  REQUIRE(config->axes[3]);
  CHECK(config->axes[3]->min == -100.0);
  CHECK(config->axes[3]->max_feed == 3600.0); // integers are accepted for numbers
  CHECK(config->axes[5]->cyclic);
  CHECK_FALSE(config->axes[4]); // no B axis
  CHECK(config->controller.line_length == 79);
  CHECK_FALSE(config->controller.rx_buffer);
  CHECK(config->controller.serial.baud == 115200);
}

TEST_CASE("a fanuc controller defaults to 7E2 with XON/XOFF") {
  const auto config = parse_machine_config(replace(trt, R"("grbl")", R"("fanuc")"), "m.toml");
  REQUIRE(config);
  CHECK(config->controller.dialect == subfeed::post::Dialect::fanuc);
  CHECK(config->controller.serial.data_bits == 7);
  CHECK(config->controller.serial.parity == subfeed::post::Parity::even);
  CHECK(config->controller.serial.stop_bits == 2);
  CHECK(config->controller.serial.flow_control == subfeed::post::FlowControl::xon_xoff);
}

TEST_CASE("unknown keys are errors naming file, line and key") {
  expect_error(trt + "colour = \"red\"\n", "m.toml:31: controller.colour: unknown key");
  expect_error(replace(trt, "y_offset", "yoffset"),
               "m.toml:6: kinematics.yoffset: unknown key; did you mean 'y_offset'?");
  expect_error(replace(trt, "y_offset = 4.0", "y_offset = 4.0\nyofset = 1"),
               "m.toml:7: kinematics.yofset: unknown key");
  expect_error(trt + "[spindle]\nmax_rpm = 24000\n", "m.toml:31: spindle: unknown key");
  expect_error(trt + "[axes.b]\nmin = 0\nmax = 1\nmax_feed = 1\n",
               "m.toml:31: axes.b: unknown key");
}

TEST_CASE("wrong types are errors naming the key and both types") {
  expect_error(replace(trt, "min = -100.0\nmax = 100.0\nmax_feed = 3000\n[axes.y]",
                       "min = \"-100\"\nmax = 100.0\nmax_feed = 3000\n[axes.y]"),
               "m.toml:11: axes.x.min: expected a number, got a string");
  expect_error(replace(trt, "cyclic = true", "cyclic = 1"),
               "m.toml:27: axes.c.cyclic: expected true or false, got an integer");
  expect_error(replace(trt, "a_direction = -1", "a_direction = -1.0"),
               "m.toml:8: kinematics.a_direction: expected an integer, got a number");
  expect_error(replace(trt, "pivot = [1.0, 2.0, 3.0]", "pivot = [1.0, 2.0]"),
               "m.toml:5: kinematics.pivot: expected an array of 3 numbers");
  expect_error(replace(trt, "[axes.z]\nmin = -100.0\nmax = 0.0\nmax_feed = 1000\n", "") +
                   "[axes]\nz = 5\n",
               "m.toml:28: axes.z: expected a table, got an integer");
}

TEST_CASE("missing required keys are errors naming the key") {
  expect_error(replace(trt, "name = \"test trunnion\"\n", ""),
               "m.toml:1: machine.name: missing required key (a string)");
  expect_error(replace(trt, "z_offset = 5.0\n", ""),
               "m.toml:4: kinematics.z_offset: missing required key (a number)");
  expect_error(replace(trt, "[axes.a]\nmin = -100.0\nmax = 50.0\nmax_feed = 3600\n", ""),
               "m.toml:10: axes.a: missing required key (a table)");
  expect_error(replace(trt, "[controller]\nprotocol = \"grbl\"\n", ""),
               "m.toml:1: controller: missing required key (a table)");
  expect_error(replace(trt, "[kinematics]\n", "[kinematics_]\n"),
               "m.toml:4: kinematics_: unknown key; did you mean 'kinematics'?");
}

TEST_CASE("values out of range are errors naming the key and the range") {
  expect_error(replace(trt, "max_feed = 1000", "max_feed = -5"),
               "m.toml:21: axes.z.max_feed: -5 mm/min is outside 0.001..1e+06 mm/min");
  expect_error(replace(trt, "max = 50.0", "max = -150.0"),
               "m.toml:24: axes.a.max: must be greater than min");
  expect_error(replace(trt, "min = -100.0\nmax = 50.0", "min = -4000.0\nmax = 50.0"),
               "m.toml:23: axes.a.min: -4000 deg is outside -3600..3600 deg");
  expect_error(replace(trt, "c_direction = 1", "c_direction = 0"),
               "m.toml:9: kinematics.c_direction: must be 1 (ISO: the tool turns by the right-hand "
               "rule) or -1 (LinuxCNC default)");
  expect_error(
      replace(trt, "kinematics = \"xyzac-trt\"", "kinematics = \"xyzbc\""),
      "m.toml:3: machine.kinematics: 'xyzbc' is not one of xyz, xyzac-trt, xyzbc-trt, xyzac-head");
  expect_error(trt + "rx_buffer = 8\n", "m.toml:31: controller.rx_buffer: 8 is outside 16..65536");
  expect_error(trt + "[controller.serial]\nbaud = 12345\n",
               "m.toml:32: controller.serial.baud: 12345 is not a standard rate (300..921600)");
  expect_error(trt + "[controller.serial]\nparity = \"mark\"\n",
               "m.toml:32: controller.serial.parity: 'mark' is not one of none, even, odd");
  expect_error(replace(trt, "name = \"test trunnion\"", "name = \"\""),
               "m.toml:2: machine.name: must not be empty");
}

TEST_CASE("contradictory settings are errors naming the key") {
  expect_error(replace(trt, "cyclic = true", "cyclic = true\nmin = 0"),
               "m.toml:28: axes.c.min: a cyclic axis has no travel limits");
  expect_error(trt + "tcp = true\n",
               "m.toml:31: controller.tcp: the grbl dialect has no tool-centre-point control");
  expect_error(trt + "program_number = 12\n",
               "m.toml:31: controller.program_number: applies to the fanuc dialect only");
  const std::string xyz = replace(replace(trt, "xyzac-trt", "xyz"),
                                  "[axes.a]\nmin = -100.0\nmax = 50.0\nmax_feed = "
                                  "3600\n[axes.c]\ncyclic = true\nmax_feed = 7200\n",
                                  "");
  expect_error(xyz, "m.toml:4: kinematics: an xyz machine has no rotary geometry");
}

TEST_CASE("TOML syntax errors name the line") {
  expect_error(replace(trt, "y_offset = 4.0", "y_offset = = 4.0"),
               "m.toml:6: TOML syntax: Error while parsing value: could not determine value type");
}

TEST_CASE("a missing config file is named") {
  const auto config = subfeed::post::load_machine_config("/nonexistent/m.toml");
  REQUIRE_FALSE(config);
  CHECK(config.error().describe() == "/nonexistent/m.toml: cannot open machine config");
}

TEST_CASE("every shipped machine config loads") {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(SUBFEED_SOURCE_DIR) + "/configs")) {
    const auto kind = subfeed::post::config_kind(entry.path());
    if (entry.path().extension() == ".toml" && kind &&
        *kind == subfeed::post::ConfigKind::machine) {
      INFO(entry.path());
      const auto config = subfeed::post::load_machine_config(entry.path());
      CHECK(config.has_value());
      ++count;
    }
  }
  CHECK(count >= 3);
}

TEST_CASE("xyzbc-trt and xyzac-head read their own geometry keys") {
  auto bc = replace(replace(replace(replace(trt, "xyzac-trt", "xyzbc-trt"), "y_offset", "x_offset"),
                            "a_direction", "b_direction"),
                    "[axes.a]", "[axes.b]");
  const auto config = parse_machine_config(bc, "m.toml");
  REQUIRE(config);
  CHECK(config->kinematics == KinematicsType::xyzbc_trt);
  CHECK(config->rotary->x_offset == 4.0);
  CHECK(config->rotary->tilt_direction == -1);
  CHECK(config->axes[4]);
  CHECK_FALSE(config->axes[3]);
  expect_error(replace(bc, "x_offset", "y_offset"),
               "m.toml:6: kinematics.y_offset: unknown key; did you mean 'x_offset'?");

  const auto head = replace(replace(trt, "xyzac-trt", "xyzac-head"),
                            "pivot = [1.0, 2.0, 3.0]\ny_offset = 4.0\nz_offset = 5.0\n",
                            "pivot_length = 150.0\n");
  const auto h = parse_machine_config(head, "m.toml");
  REQUIRE(h);
  CHECK(h->rotary->pivot_length == 150.0);
  expect_error(replace(head, "pivot_length = 150.0", "pivot_length = -1.0"),
               "m.toml:5: kinematics.pivot_length: -1 mm is outside 0..10000 mm");
}

TEST_CASE("the [post] table: defaults, values and errors") {
  const auto plain = parse_machine_config(trt, "m.toml");
  REQUIRE(plain);
  CHECK(plain->post.singularity_cone == 0.05);
  CHECK(plain->post.retract == 5.0);
  CHECK_FALSE(plain->post.safe_z);
  const auto with_post = trt + "[post]\nsingularity_cone = 0.2\nretract = 8\nsafe_z = -10.0\n"
                               "preferred_tilt = \"negative\"\n";
  const auto config = parse_machine_config(with_post, "m.toml");
  REQUIRE(config);
  CHECK(config->post.singularity_cone == 0.2);
  CHECK(config->post.retract == 8.0);
  CHECK(config->post.safe_z == -10.0);
  CHECK(config->post.preferred_tilt == -1);
  expect_error(replace(with_post, "safe_z = -10.0", "safe_z = 10.0"),
               "m.toml:34: post.safe_z: must lie within the Z travel limits");
  expect_error(replace(with_post, "\"negative\"", "\"down\""),
               "m.toml:35: post.preferred_tilt: 'down' is not one of positive, negative, either");
}

TEST_CASE("a machine's tilt range is its tilt axis's reach in every direction round C", "[unit]") {
  const std::string dir = std::string(SUBFEED_SOURCE_DIR) + "/configs/";
  const auto range = [&](const std::string& name) {
    const auto config = subfeed::post::load_machine_config(dir + name);
    REQUIRE(config);
    return subfeed::post::tilt_range_deg(*config);
  };
  CHECK_FALSE(range("grbl-router-3axis.toml"));
  CHECK(range("grblhal-xyzac-trt.toml") == 100.0);  // A -100..50, C endless
  CHECK(range("fanuc-xyzac-trt.toml") == 120.0);    // A -120..30, C endless
  CHECK(range("grblhal-xyzac-head.toml") == 95.0);  // A -95..95, C a turn each way
  CHECK(range("linuxcnc-xyzbc-trt.toml") == 110.0); // B -110..110, C endless
  // C less than a turn: a direction may need the other sign of A, so the smaller side.
  const auto half_turn =
      replace(trt, "[axes.c]\ncyclic = true", "[axes.c]\nmin = -90.0\nmax = 90.0");
  const auto limited = parse_machine_config(half_turn, "m.toml");
  REQUIRE(limited);
  REQUIRE_FALSE(limited->axes[5]->cyclic);
  CHECK(subfeed::post::tilt_range_deg(*limited) == 50.0); // A -100..50
  // And a tilt one way only can reach no direction C does not turn it to.
  const auto one_way = parse_machine_config(
      replace(half_turn, "[axes.a]\nmin = -100.0", "[axes.a]\nmin = 0.0"), "m.toml");
  REQUIRE(one_way);
  CHECK(subfeed::post::tilt_range_deg(*one_way) == 0.0);
}
