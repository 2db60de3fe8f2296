// Post-processing figures, each beside a baseline from the same run:
//   poses per second posted (IK, solution choice, splitting, G-code text)  vs reading the CL alone
//   blocks per second checked (forward kinematics replay against the CL)  vs reading the CL alone
//   peak memory posting and checking 10 million poses                     vs after 100,000
// on a 5-axis spiral over a sphere for the grblHAL trunnion (configs/grblhal-xyzac-trt.toml).
// SUBFEED_BENCH_POSES overrides the 10 million.

#include "bench_harness.hpp"

#include "cl/cl_reader.hpp"
#include "cl/cl_writer.hpp"
#include "post/post_file.hpp"
#include "post/program_check.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

namespace {

using namespace subfeed;
namespace fs = std::filesystem;

fs::path write_cl(long poses) {
  const auto path = fs::temp_directory_path() / ("subfeed-bench-" + std::to_string(poses) + ".cl");
  auto writer = cl::ClWriter::create(path, {"BENCH", {6.0, 3.0}, true, {}, {}});
  if (!writer) {
    std::abort();
  }
  constexpr double deg = std::numbers::pi / 180.0;
  for (long i = 0; i <= poses; ++i) {
    // Tilt rises 5..45 deg and falls again every 20,000 poses while the azimuth turns.
    const double s = static_cast<double>(i % 20000) / 20000.0;
    const double tilt = (5.0 + 40.0 * std::sin(std::numbers::pi * s)) * deg;
    const double azimuth = static_cast<double>(i) * 0.05 * deg;
    const std::array<double, 3> n{std::sin(tilt) * std::cos(azimuth),
                                  std::sin(tilt) * std::sin(azimuth), std::cos(tilt)};
    writer->write({{25 * n[0], 25 * n[1], -10 + 25 * n[2]},
                   n,
                   i == 0 ? cl::MoveKind::rapid : cl::MoveKind::feed,
                   i == 0 ? 0.0 : 1500.0,
                   0});
  }
  if (!writer->finish()) {
    std::abort();
  }
  return path;
}

long read_all(const fs::path& cl) {
  auto reader = cl::ClReader::open(cl);
  long n = 0;
  while (reader) {
    auto pose = reader->next();
    if (!pose || !*pose) {
      break;
    }
    ++n;
  }
  return n;
}

struct Run {
  long poses = 0;
  long blocks = 0;
  double post_seconds = 0.0;
  double check_seconds = 0.0;
  double tip_deviation = 0.0;
};

Run post_and_check(const fs::path& cl, const post::MachineConfig& machine) {
  const auto nc = fs::path(cl).replace_extension(".nc");
  post::PostFileOptions options;
  options.program = post::program_options_for(machine);
  Run run;
  run.post_seconds = bench::best_seconds(1, [&] {
    auto summary = post::post_file(cl, machine, options, nc);
    if (!summary) {
      std::fprintf(stderr, "%s\n", summary.error().describe().c_str());
      std::abort();
    }
    run.poses = summary->stats.poses;
    run.blocks = summary->lines;
  });
  post::CheckOptions check;
  check.cl = cl;
  run.check_seconds = bench::best_seconds(1, [&] {
    auto report = post::check_program(nc, machine, check);
    if (!report) {
      std::abort();
    }
    run.tip_deviation = report->tip_deviation.value;
  });
  fs::remove(nc);
  fs::remove(post::map_path_for(nc));
  return run;
}

} // namespace

int main() {
  const auto machine =
      post::load_machine_config(fs::path(SUBFEED_SOURCE_DIR) / "configs/grblhal-xyzac-trt.toml");
  if (!machine) {
    return 1;
  }
  {
    const auto cl = write_cl(1'000'000);
    long read = 0;
    const double read_seconds = bench::best_seconds(3, [&] { read = read_all(cl); });
    const auto run = post_and_check(cl, *machine);
    bench::report({"poses posted per second", run.poses / run.post_seconds, "poses/s",
                   "CL poses read per second", read / read_seconds, true});
    bench::report({"blocks checked per second", run.blocks / run.check_seconds, "blocks/s",
                   "CL poses read per second", read / read_seconds, true});
    std::printf("  (%ld poses -> %ld lines, worst tip deviation %.6f mm)\n", run.poses, run.blocks,
                run.tip_deviation);
    fs::remove(cl);
  }
  const char* env = std::getenv("SUBFEED_BENCH_POSES");
  const long poses = env != nullptr ? std::atol(env) : 10'000'000L;
  const auto small = write_cl(100'000);
  (void)post_and_check(small, *machine);
  fs::remove(small);
  const double baseline = bench::peak_rss_mib();
  const auto big = write_cl(poses);
  const auto run = post_and_check(big, *machine);
  fs::remove(big);
  bench::report({"peak RSS, " + std::to_string(poses) + " poses", bench::peak_rss_mib(), "MiB",
                 "peak RSS, 100000 poses", baseline, false});
  std::printf("  (%ld poses -> %ld lines: post %.1f s, check %.1f s)\n", run.poses, run.blocks,
              run.post_seconds, run.check_seconds);
  return 0;
}
