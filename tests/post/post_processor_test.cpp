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
  auto writer = cl::ClWriter::create(file, {"SPHERE", {6.0, 3.0}, true, {}, {}});
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

TEST_CASE("past the pole just outside the cone: the continuous branch, no C swing in one block") {
  // The tool axis sweeps along a straight line in the tangent plane that misses the pole by
  // `miss` deg, a little more than the 0.05 deg cone, in a few coarse steps as a planner's
  // passes do over a flat top. The endpoints' nearest solutions lie on opposite branches
  // (A changes sign, C differs by less than the azimuth does), but no continuous joint motion
  // joins them: the post must follow the azimuth with C instead.
  TempDir dir;
  const auto machine = trunnion();
  for (const double miss : {0.06, 0.071, 0.2}) {
    CAPTURE(miss);
    const auto cl = sphere_cl(
        dir,
        [miss](double s) {
          const double u = -0.5 + s; // deg along the line; the pole is passed between poses
          return std::array{std::hypot(u, miss), std::atan2(miss, u) / deg};
        },
        7);
    const auto posted = post_and_check(cl, machine);
    require_clean(posted.check);
  }
}

TEST_CASE("near the pole far from the C axis: the tip does not run past a segment's end") {
  // A pass the planner made over the bench's wavy part, verbatim: 55 mm from the C axis the
  // tool tilts 0.2 deg per 0.55 mm step past the pole at 0.6 deg, so C turns ~5 deg a block
  // while the tip creeps. Joint-linear motion then carries the tip past the segment's end
  // late in the block (4 um), where sampling a block at its quarters does not look.
  TempDir dir;
  const auto machine = post::load_machine_config(std::string(SUBFEED_SOURCE_DIR) +
                                                 "/configs/grblhal-xyzac-trt.toml");
  REQUIRE(machine);
  const auto file = dir.path() / "pass.cl";
  std::ofstream(file)
      << "PARTNO WAVY\nUNITS/MM\nCUTTER/6.,3.\nMULTAX/ON\nRAPID\n"
         "GOTO/-79.768297,-4.891411,1.986534,0.114894888,0.000780367,0.993377348\n"
         "FEDRAT/1000.\n"
         "GOTO/-59.999258,-4.920881,-1.806646,0.041853718,0.009912175,0.999074579\n"
         "GOTO/-59.445754,-4.921416,-1.828957,0.038891837,0.010005357,0.999193334\n"
         "GOTO/-58.890265,-4.922019,-1.849313,0.035238581,0.010149936,0.999327384\n"
         "GOTO/-58.334750,-4.922514,-1.867617,0.031546768,0.010272322,0.999449489\n"
         "GOTO/-57.777372,-4.923004,-1.883903,0.027204644,0.010410445,0.999575675\n"
         "GOTO/-57.220033,-4.922902,-1.898093,0.022845783,0.010517512,0.999683676\n"
         "GOTO/-56.664613,-4.923037,-1.910130,0.019097050,0.010564085,0.999761823\n"
         "GOTO/-56.109154,-4.923159,-1.920050,0.015306362,0.010583291,0.999826840\n"
         "GOTO/-55.553617,-4.923357,-1.927839,0.011460430,0.010616572,0.999877966\n"
         "GOTO/-54.999930,-4.923514,-1.933465,0.008202285,0.010638651,0.999909767\n"
         "GOTO/-54.446594,-4.923820,-1.936940,0.005051594,0.010643137,0.999930600\n"
         "GOTO/-53.891122,-4.924098,-1.938276,0.001199093,0.010671825,0.999942335\n"
         "GOTO/-53.335692,-4.924271,-1.937460,-0.002629261,0.010682472,0.999939484\n"
         "GOTO/-52.778172,-4.924404,-1.934484,-0.007143544,0.010698793,0.999917249\n"
         "GOTO/-52.220635,-4.923872,-1.929357,-0.011653269,0.010675067,0.999875114\n"
         "GOTO/-51.665232,-4.923681,-1.922107,-0.015440834,0.010613601,0.999824451\n"
         "GOTO/-51.109784,-4.923483,-1.912728,-0.019232371,0.010524914,0.999759642\n"
         "GOTO/-50.554261,-4.923367,-1.901222,-0.023038121,0.010450578,0.999679964\n"
         "GOTO/-50.000531,-4.923270,-1.887645,-0.026234497,0.010384421,0.999601878\n"
         "GOTO/-49.447126,-4.923333,-1.871979,-0.029292834,0.010304156,0.999517761\n"
         "GOTO/-48.891634,-4.923295,-1.854173,-0.032997420,0.010225944,0.999403122\n"
         "FINI\n";
  const auto posted = post_and_check(file, *machine, true, 256);
  require_clean(posted.check);
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

TEST_CASE("a reposition beside the pole re-approaches on the branch it turned to") {
  // C travels -200..200 and starts at 0 (no look-ahead). A sweep at 30 deg tilt takes C to
  // -80; then the tool runs along a line in the tangent plane that misses the pole by
  // 0.5 deg in 2 deg steps: C must turn -180 more, 127 of them in the one segment beside the
  // pole, and runs out of travel there. The post retracts and comes back on the other branch;
  // the last pose's solution nearest to the new one is still on the old branch there.
  TempDir dir;
  const auto machine = trunnion("min = -200.0\nmax = 200.0\nmax_feed = 20000\n");
  const auto cl = sphere_cl(
      dir,
      [](double s) {
        const int i = static_cast<int>(std::lround(s * 70.0));
        if (i <= 40) {
          return std::array{30.0, -90.0 - 80.0 * i / 40.0};
        }
        const double v = -31.0 + 2.0 * (i - 40); // deg along the line
        const double dx = std::cos(10.0 * deg), dy = std::sin(10.0 * deg);
        const double x = -0.5 * dy + v * dx, y = 0.5 * dx + v * dy;
        return std::array{std::hypot(x, y), std::atan2(y, x) / deg};
      },
      70);
  const auto posted = post_and_check(cl, machine, false);
  require_clean(posted.check);
  CHECK(posted.summary.stats.repositions >= 1);
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
