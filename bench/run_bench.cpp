// The whole job as a user runs it: the real `subfeed` binary in a child process, streaming to
// its simulated controller at unlimited speed (no wire, no motion time). Figures:
//  - end-to-end blocks per second of `run` against each stage alone on the same job (plan,
//    post, send): the pipeline can at best match its slowest stage;
//  - time to the first block against planning alone (what a tool that plans first waits);
//  - peak memory of `run` for 10,000,000 CL points against 100,000 (goal: flat, < 200 MiB).
// The memory jobs run existing CL data on a three-axis machine, so that a block is a point:
// the planner's own memory grows with the part's area over the tolerance (its mesh), which
// the planning figure shows separately.

#include "bench_harness.hpp"
#include "child_process.hpp"
#include "wavy_cage.hpp"

#include "cl/cl_writer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <spawn.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>


namespace {

using namespace subfeed;
namespace fs = std::filesystem;

const std::string source = SUBFEED_SOURCE_DIR;
const std::string subfeed_binary = SUBFEED_BINARY;

using bench::Child;

// Runs `subfeed args...`; exits the bench if it fails.
Child run_subfeed(const std::vector<std::string>& args, const fs::path& dir) {
  std::vector<std::string> all{subfeed_binary};
  all.insert(all.end(), args.begin(), args.end());
  auto child = bench::run_child(all, dir);
  if (!child.started) {
    std::fprintf(stderr, "bench_run: cannot start %s\n", subfeed_binary.c_str());
    std::exit(1);
  }
  if (child.exit_code != 0) {
    std::fprintf(stderr, "bench_run: `subfeed %s` failed:\n%s\n", args.front().c_str(),
                 child.err.c_str());
    std::exit(1);
  }
  return child;
}

// A number from the JSON event `event` in `text`, e.g. ("job", "lines").
double json_number(const std::string& text, std::string_view event, std::string_view key) {
  const auto at = text.find(fmt::format("\"event\":\"{}\"", event));
  const auto field = text.find(fmt::format("\"{}\":", key), at);
  if (at == std::string::npos || field == std::string::npos) {
    std::fprintf(stderr, "bench_run: no %.*s.%.*s in the output\n", static_cast<int>(event.size()),
                 event.data(), static_cast<int>(key.size()), key.data());
    std::exit(1);
  }
  return std::strtod(text.c_str() + field + key.size() + 3, nullptr);
}

long count_lines(const fs::path& file) {
  const auto text = bench::slurp(file);
  return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}

std::vector<std::string> sim_flags() {
  return {"--sim-speed", "1000000", "--sim-baud", "0", "--json"};
}

void bench_stages(const fs::path& dir) {
  const auto cage = dir / "wavy.obj";
  std::ofstream(cage) << bench::wavy_grid_obj(33, 5.0, 2.0, true);
  const std::string machine = source + "/configs/grblhal-xyzac-trt.toml";
  const std::vector<std::string> job{"--tool", "ball:6", "--scallop", "0.01"};

  auto args = std::vector<std::string>{"plan", cage.string(), "-o", (dir / "alone.cl").string()};
  args.insert(args.end(), job.begin(), job.end());
  const Child plan = run_subfeed(args, dir);
  const Child post = run_subfeed({"post", (dir / "alone.cl").string(), "--machine", machine, "-o",
                                  (dir / "alone.nc").string()},
                                 dir);
  const long lines = count_lines(dir / "alone.nc");
  args = {"send", (dir / "alone.nc").string(), "--sim", "grblhal"};
  for (const auto& f : sim_flags()) {
    args.push_back(f);
  }
  const Child send = run_subfeed(args, dir);
  args = {"run", cage.string(), "--machine", machine, "--sim", "-o", (dir / "job").string()};
  args.insert(args.end(), job.begin(), job.end());
  for (const auto& f : sim_flags()) {
    args.push_back(f);
  }
  const Child run = run_subfeed(args, dir);

  const double run_lines = json_number(run.out, "job", "lines");
  const double run_rate = run_lines / json_number(run.out, "job", "streamed_s");
  const double plan_rate = static_cast<double>(lines) / plan.seconds;
  const double post_rate = static_cast<double>(lines) / post.seconds;
  const double send_rate = static_cast<double>(lines) / send.seconds;
  std::printf("job: wavy 1,024-face part, ball 6 mm, H 0.01 mm, grblHAL A/C trunnion: %.0f "
              "blocks; alone: plan %.2f s, post %.2f s, send %.2f s\n",
              run_lines, plan.seconds, post.seconds, send.seconds);
  const double fastest = std::max({plan_rate, post_rate, send_rate});
  const double slowest = std::min({plan_rate, post_rate, send_rate});
  bench::report({"run end to end", run_rate, "blocks/s", "fastest stage alone", fastest});
  bench::report({"run end to end", run_rate, "blocks/s", "slowest stage alone", slowest});
  bench::report({"time to first block", json_number(run.out, "job", "first_block_s"), "s",
                 "planning alone", plan.seconds, false});
  bench::report({"time to first move", json_number(run.out, "job", "first_move_s"), "s",
                 "planning alone", plan.seconds, false});
  bench::report(
      {"peak memory, run of that job", run.peak_mib, "MiB", "plan alone", plan.peak_mib, false});
}

// A zig-zag raster of `points` points over 600 x 500 mm, heights on gentle waves, for a
// three-axis machine: one block per point.
void write_raster(const fs::path& file, long points) {
  auto writer = cl::ClWriter::create(file, {"RASTER", {6.0, 3.0}, false, {}, {}}).value();
  const long rows = std::max(2L, static_cast<long>(std::sqrt(points / 2.5)));
  const long columns = points / rows;
  const auto z = [](double x, double y) {
    return -5.0 + 2.0 * std::sin(x / 20.0) * std::cos(y / 30.0);
  };
  writer.write({{-300.0, -250.0, 10.0}, {0, 0, 1}, cl::MoveKind::rapid, 0.0, 0});
  for (long r = 0; r < rows; ++r) {
    const double y = -250.0 + 500.0 * static_cast<double>(r) / static_cast<double>(rows - 1);
    for (long c = 0; c < columns; ++c) {
      const long k = r % 2 == 0 ? c : columns - 1 - c;
      const double x = -300.0 + 600.0 * static_cast<double>(k) / static_cast<double>(columns - 1);
      writer.write({{x, y, z(x, y)}, {0, 0, 1}, cl::MoveKind::feed, 3000.0, 0});
    }
  }
  (void)writer.finish().value();
}

// A flat floor 10 mm below the raster's waves (the ball stays 2 mm above it): the cage the
// motion gate checks the raster against.
void write_floor(const fs::path& file) {
  std::ofstream out(file);
  for (int j = 0; j <= 6; ++j) {
    for (int i = 0; i <= 7; ++i) {
      out << "v " << -350 + 100 * i << ' ' << -300 + 100 * j << " -10\n";
    }
  }
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 7; ++i) {
      const int v = j * 8 + i + 1;
      out << "f " << v << ' ' << v + 1 << ' ' << v + 9 << ' ' << v + 8 << '\n';
    }
  }
}

double run_raster_mib(const fs::path& dir, long points) {
  const auto cl = dir / "raster.cl";
  write_raster(cl, points);
  const auto floor = dir / "floor.obj";
  write_floor(floor);
  std::vector<std::string> args{
      "run",          cl.string(), "--cage",
      floor.string(), "--machine", source + "/configs/grbl-router-3axis.toml",
      "--sim",        "-o",        (dir / "raster").string()};
  for (const auto& f : sim_flags()) {
    args.push_back(f);
  }
  const Child run = run_subfeed(args, dir);
  std::printf("raster of %ld CL points: %.0f blocks in %.1f s (%.0f blocks/s), peak %.1f MiB\n",
              points, json_number(run.out, "job", "lines"), run.seconds,
              json_number(run.out, "job", "lines") / json_number(run.out, "job", "streamed_s"),
              run.peak_mib);
  for (const char* ext : {".cl", ".nc", ".nc.map", ".journal"}) {
    fs::remove(dir / (std::string("raster") + ext));
  }
  return run.peak_mib;
}

} // namespace

int main() {
  const auto dir = fs::temp_directory_path() / ("subfeed-run-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  bench_stages(dir);
  const double small = run_raster_mib(dir, 100'000);
  const double large = run_raster_mib(dir, 10'000'000);
  bench::report(
      {"peak memory, run of 10M CL points", large, "MiB", "run of 100k CL points", small, false});
  fs::remove_all(dir);
  return 0;
}
