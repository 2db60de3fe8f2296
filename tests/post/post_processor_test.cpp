// The post against its own independent replay (program_check): every test posts real CL
// data for a machine, then replays the G-code through forward kinematics and measures.

#include "cl/cl_writer.hpp"
#include "post/machine_config.hpp"
#include "post/post_file.hpp"
#include "post/program_check.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>

using namespace subfeed;
using subfeed::testing::TempDir;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// An A/C trunnion with ISO signs; `c_axis` is the TOML body of [axes.c].
post::MachineConfig trunnion(const std::string& c_axis = "cyclic = true\nmax_feed = 20000\n",
                             const std::string& a_limits = "min = -100.0\nmax = 50.0\n") {
  const std::string text = "[machine]\nname = \"test trunnion\"\nkinematics = \"xyzac-trt\"\n"
                           "[kinematics]\npivot = [0.0, 0.0, -50.0]\ny_offset = 2.0\n"
                           "z_offset = 30.0\na_direction = 1\nc_direction = 1\n"
                           "[axes.x]\nmin = -500.0\nmax = 500.0\nmax_feed = 20000\n"
                           "[axes.y]\nmin = -500.0\nmax = 500.0\nmax_feed = 20000\n"
                           "[axes.z]\nmin = -500.0\nmax = 200.0\nmax_feed = 20000\n"
                           "[axes.a]\n" +
                           a_limits +
                           "max_feed = 20000\n"
                           "[axes.c]\n" +
                           c_axis +
                           "[controller]\nprotocol = \"grbl\"\nline_length = 256\ndecimals = 4\n";
  auto config = post::parse_machine_config(text, "test.toml");
  REQUIRE(config);
  return *config;
}

std::array<double, 3> direction(double tilt_deg, double azimuth_deg) {
  return {std::sin(tilt_deg * deg) * std::cos(azimuth_deg * deg),
          std::sin(tilt_deg * deg) * std::sin(azimuth_deg * deg), std::cos(tilt_deg * deg)};
}

// CL data on a sphere of radius 25 about (0, 0, -10), the tool normal to it, at the
// (tilt, azimuth) pairs `path` gives for s = 0..1; a rapid above the start first.
std::filesystem::path sphere_cl(const TempDir& dir,
                                const std::function<std::array<double, 2>(double)>& path, int poses,
                                const std::string& name = "part.cl") {
  const auto file = dir.path() / name;
  auto writer = cl::ClWriter::create(file, {"SPHERE", {6.0, 3.0}, true});
  REQUIRE(writer);
  for (int i = 0; i <= poses; ++i) {
    const auto [tilt, azimuth] = path(static_cast<double>(i) / poses);
    const auto n = direction(tilt, azimuth);
    const double r = i == 0 ? 30.0 : 25.0;
    writer->write({{r * n[0], r * n[1], -10.0 + r * n[2]},
                   n,
                   i == 0 ? cl::MoveKind::rapid : cl::MoveKind::feed,
                   i == 0 ? 0.0 : 1500.0,
                   0});
  }
  REQUIRE(writer->finish());
  return file;
}

struct Posted {
  post::PostFileSummary summary;
  post::CheckReport check;
};

Posted post_and_check(const std::filesystem::path& cl, const post::MachineConfig& machine,
                      bool look_ahead = true, int samples = 64) {
  post::PostFileOptions options;
  options.program = post::program_options_for(machine);
  options.look_ahead = look_ahead;
  const auto nc = std::filesystem::path(cl).replace_extension(".nc");
  auto summary = post::post_file(cl, machine, options, nc);
  REQUIRE(summary);
  post::CheckOptions check;
  check.cl = cl;
  check.samples_per_block = samples;
  auto report = post::check_program(nc, machine, check);
  REQUIRE(report);
  return {*summary, *report};
}

void require_clean(const post::CheckReport& r) {
  CHECK(r.tip_deviation.value <= 0.002);
  CHECK(r.axis_deviation.value <= r.allowed_axis_deviation);
  CHECK(r.limit_violations == 0);
  CHECK(r.rotary_jumps == 0);
  CHECK(r.over_feed == 0);
  CHECK(r.passed(0.002));
}

} // namespace

TEST_CASE("linearization keeps the tool tip within 2 um of the CL segments, sampled densely") {
  TempDir dir;
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{60.0 * s, 4 * 360.0 * s};
      },
      400);
  const auto posted = post_and_check(cl, trunnion(), true, 200);
  require_clean(posted.check);
  CHECK(posted.summary.stats.splits > 0);
  CHECK(posted.check.cut_blocks_compared > 400);
  CHECK(posted.check.tip_deviation.value > 1e-4); // the check measures something real
}

TEST_CASE("a check of a tampered program fails on the tampered line") {
  TempDir dir;
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{40.0, 90.0 * s};
      },
      50);
  const auto machine = trunnion();
  const auto posted = post_and_check(cl, machine);
  require_clean(posted.check);
  const auto nc = std::filesystem::path(cl).replace_extension(".nc");
  std::ifstream in(nc);
  std::stringstream out;
  std::string line;
  int n = 0, tampered = 0;
  while (std::getline(in, line)) {
    ++n;
    if (tampered == 0 && n > 20 && (line.starts_with("X") || line.starts_with("Y"))) {
      line = line.substr(0, 1) + std::to_string(std::stod(line.substr(1)) + 0.01) +
             line.substr(line.find(' '));
      tampered = n;
    }
    out << line << '\n';
  }
  in.close();
  std::ofstream(nc) << out.str();
  post::CheckOptions check;
  check.cl = cl;
  const auto report = post::check_program(nc, machine, check);
  REQUIRE(report);
  CHECK_FALSE(report->passed(0.002));
  CHECK(report->tip_deviation.value > 0.005);
  CHECK((report->tip_deviation.line == tampered || report->tip_deviation.line == tampered + 1));
}

TEST_CASE("through the pole: C holds still in the cone and no rotary axis jumps") {
  TempDir dir;
  const auto machine = trunnion();
  SECTION("straight over the pole") {
    const auto cl = sphere_cl(
        dir,
        [](double s) {
          return std::array{std::abs(60.0 * s - 30.0), s < 0.5 ? 180.0 : 0.0};
        },
        200);
    const auto posted = post_and_check(cl, machine);
    require_clean(posted.check);
  }
  SECTION("just beside the pole, inside the cone") {
    // Azimuth sweeps 180 deg while the tilt stays 0.02 deg: the tool is within the 0.05 deg
    // cone, so C must not chase the azimuth.
    const auto cl = sphere_cl(
        dir,
        [](double s) {
          return std::array{0.02, 180.0 * s};
        },
        50);
    const auto posted = post_and_check(cl, machine);
    require_clean(posted.check);
    CHECK(posted.summary.stats.cone_poses == 50);
    CHECK(posted.summary.stats.max_axis_hold <= 0.05);
  }
}

TEST_CASE("a limited C axis: the look-ahead picks the turn that needs no unwinding") {
  // One and a half turns of C; C travels -400..400 deg. Starting at C near 0 the path runs
  // out of travel; starting one turn back it fits.
  TempDir dir;
  const auto machine = trunnion("min = -400.0\nmax = 400.0\nmax_feed = 20000\n");
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{30.0, 540.0 * s};
      },
      300);
  const auto planned = post_and_check(cl, machine, true);
  require_clean(planned.check);
  CHECK(planned.summary.stats.repositions == 0);
  const auto greedy = post_and_check(cl, machine, false);
  require_clean(greedy.check);
  CHECK(greedy.summary.stats.repositions >= 1);
}

TEST_CASE("where no start avoids it: retract, unwind, re-approach, and no jump while cutting") {
  // C travels -200..200 deg and the path turns two full turns: at least one unwind.
  TempDir dir;
  const auto machine = trunnion("min = -200.0\nmax = 200.0\nmax_feed = 20000\n");
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{30.0, 720.0 * s};
      },
      400);
  const auto posted = post_and_check(cl, machine);
  require_clean(posted.check);
  CHECK(posted.summary.stats.repositions >= 1);
}

TEST_CASE("a branch change forced by the C travel: both branches, one retract") {
  // C travels -90..90. With ISO signs a tool leaning toward azimuth z needs C = z + 90 (A > 0)
  // or C = z - 90 (A < 0): azimuths -90..80 need C = 0..170 or -180..-10, and neither
  // branch fits the whole sweep.
  TempDir dir;
  const auto machine = trunnion("min = -90.0\nmax = 90.0\nmax_feed = 20000\n");
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{30.0, -90.0 + 170.0 * s};
      },
      170);
  const auto posted = post_and_check(cl, machine);
  require_clean(posted.check);
  CHECK(posted.summary.stats.repositions == 1);
}

TEST_CASE("a pose out of reach is an error naming its CL line, and no output is left") {
  TempDir dir;
  const auto machine = trunnion();
  // Tilt grows to 110 deg: beyond A's -100..50 on both branches.
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{110.0 * s, 0.0};
      },
      110);
  post::PostFileOptions options;
  options.program = post::program_options_for(machine);
  const auto nc = dir.path() / "part.nc";
  const auto result = post::post_file(cl, machine, options, nc);
  REQUIRE_FALSE(result);
  // Pose i sits on line 6 + i (header 4 lines, RAPID + first GOTO, then FEDRAT); tilt 100.x
  // is pose 101.
  CHECK_THAT(result.error().describe(),
             Catch::Matches(".*part\\.cl:[0-9]+: pose out of the machine's reach: A would be "
                            "-10[0-9]\\.[0-9]+ outside its travel -100\\.000\\.\\.50\\.000"));
  CHECK_FALSE(std::filesystem::exists(nc));
  CHECK_FALSE(std::filesystem::exists(post::map_path_for(nc)));
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 1); // the CL file alone
}

TEST_CASE("a 3-axis machine refuses a tilted tool") {
  TempDir dir;
  auto machine = post::load_machine_config(std::string(SUBFEED_SOURCE_DIR) +
                                           "/configs/grbl-router-3axis.toml");
  REQUIRE(machine);
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        return std::array{10.0 * s, 0.0};
      },
      10);
  post::PostFileOptions options;
  options.program = post::program_options_for(*machine);
  const auto result = post::post_file(cl, *machine, options, dir.path() / "p.nc");
  REQUIRE_FALSE(result);
  CHECK_THAT(result.error().describe(), Catch::Contains("cannot point the tool that way"));
}
