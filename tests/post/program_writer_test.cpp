// Golden outputs per dialect: tests/post/golden/tilt.cl posted for the shipped machines must
// give exactly the reviewed programs beside it. Regenerate them only after reading the diff.

#include "post/machine_config.hpp"
#include "post/post_file.hpp"
#include "post/program_writer.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

const std::string source = SUBFEED_SOURCE_DIR;

void compare_golden(const std::string& config, const std::string& golden,
                    const std::function<void(post::PostFileOptions&)>& adjust) {
  auto machine = post::load_machine_config(source + "/configs/" + config);
  REQUIRE(machine);
  post::PostFileOptions options;
  options.program = post::program_options_for(*machine);
  adjust(options);
  TempDir dir;
  const auto out = dir.path() / "out.nc";
  REQUIRE(post::post_file(source + "/tests/post/golden/tilt.cl", *machine, options, out));
  CHECK(subfeed::testing::read_text(out) ==
        subfeed::testing::read_text(source + "/tests/post/golden/" + golden));
  CHECK(subfeed::testing::read_text(post::map_path_for(out)) ==
        subfeed::testing::read_text(source + "/tests/post/golden/" + golden + ".map"));
}

} // namespace

TEST_CASE("golden output: grbl dialect for the grblHAL trunnion") {
  compare_golden("grblhal-xyzac-trt.toml", "tilt-grbl.nc", [](auto&) {});
}

TEST_CASE("golden output: fanuc dialect with N numbers, comments and spindle") {
  compare_golden("fanuc-xyzac-trt.toml", "tilt-fanuc.nc", [](post::PostFileOptions& o) {
    o.program.line_numbers = true;
    o.program.comments = true;
    o.program.spindle_rpm = 12000;
  });
}

TEST_CASE("golden output: linuxcnc dialect") {
  compare_golden("fanuc-xyzac-trt.toml", "tilt-linuxcnc.nc", [](post::PostFileOptions& o) {
    o.program.dialect = post::Dialect::linuxcnc;
    o.program.comments = true;
  });
}

TEST_CASE("golden output: fanuc with tool-centre-point control (G43.4)") {
  compare_golden("fanuc-xyzac-trt.toml", "tilt-fanuc-tcp.nc",
                 [](post::PostFileOptions& o) { o.post.tcp = post::TcpMode::angles; });
}

namespace {

std::vector<std::string> write_blocks(post::ProgramOptions options,
                                      const std::vector<post::MotionBlock>& blocks,
                                      std::string* error = nullptr) {
  post::AxisSet axes;
  for (std::size_t i = 0; i < 6; ++i) {
    axes[i] = post::AxisLimits{-100, 100, 1000, false};
  }
  std::vector<std::string> lines;
  post::ProgramWriter writer(options, axes,
                             [&](std::string_view line, long, bool) { lines.emplace_back(line); });
  auto run = [&]() -> Expected<void> {
    SUBFEED_TRY(writer.begin());
    for (const auto& b : blocks) {
      SUBFEED_TRY(writer.write(b));
    }
    return writer.end();
  };
  if (auto done = run(); !done && error != nullptr) {
    *error = std::to_string(done.error().where.line) + ": " + done.error().message;
  }
  return lines;
}

post::MotionBlock linear(double x, double feed, post::FeedMode mode = post::FeedMode::per_minute) {
  post::MotionBlock b;
  b.axes[0] = x;
  b.axes[1] = 5.0;
  b.feed = feed;
  b.feed_mode = mode;
  b.cl_line = 7;
  return b;
}

} // namespace

TEST_CASE("modal words are written once, F on every inverse-time block") {
  post::ProgramOptions options;
  const auto lines =
      write_blocks(options, {linear(1, 100), linear(2, 100), linear(3, 50.0),
                             linear(4, 2.5, post::FeedMode::inverse_time),
                             linear(5, 2.5, post::FeedMode::inverse_time), linear(6, 50.0)});
  REQUIRE(lines.size() == 8);
  CHECK(lines[1] == "G1 X1. Y5. F100.");
  CHECK(lines[2] == "X2.");
  CHECK(lines[3] == "X3. F50.");
  CHECK(lines[4] == "G93 X4. F2.5");
  CHECK(lines[5] == "X5. F2.5");
  CHECK(lines[6] == "G94 X6. F50."); // F again after the mode change
  CHECK(lines[7] == "M2");
}

TEST_CASE("a block longer than the controller's line is an error naming the CL line") {
  post::ProgramOptions options;
  options.line_length = 16;
  std::string error;
  (void)write_blocks(options, {linear(12.3456, 1234.5)}, &error);
  CHECK(error == "7: block 'G1 X12.346 Y5. F1234.5' is longer than the controller's 16 "
                 "characters (controller.line_length)");
}

TEST_CASE("fanuc comments are folded into ISO 840") {
  post::ProgramOptions options;
  options.dialect = post::Dialect::fanuc;
  options.comments = true;
  options.title = "Bracket {v2} äb";
  options.program_number = 42;
  const auto lines = write_blocks(options, {});
  REQUIRE(lines.size() >= 2);
  CHECK(lines[0] == "%");
  CHECK(lines[1] == "O0042(BRACKET  V2    B)");
  CHECK(lines.back() == "%");
}
