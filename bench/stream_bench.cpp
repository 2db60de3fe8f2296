// GRBL streaming figures, each beside a baseline from the same run:
//   link use with character counting at 115200 baud   vs send-and-wait
//   host CPU per streamed line                         vs reading and preparing the line alone
//   error:N arriving -> '!' on the wire (p99)          vs one byte across the pty (p99)
//   realtime byte latency with a full queue (p99)      vs one byte across the pty (p99)
//   peak memory streaming 10 million lines             vs peak memory after 100,000 lines
// SUBFEED_BENCH_LINES overrides the 10 million.

#include "bench_harness.hpp"

#include "drivers/gcode_source.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/serial_port.hpp"
#include "sim/grbl_sim.hpp"
#include "sim/pty.hpp"

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

namespace {

using namespace subfeed;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

class Quiet final : public drivers::StreamObserver {};

std::filesystem::path write_program(long lines, unsigned seed) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("subfeed-bench-" + std::to_string(lines) + "-" + std::to_string(seed) + ".nc");
  std::ofstream out(path);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(0.0, 100.0);
  out << "G21G90\nG1F3000\n";
  char line[64];
  for (long i = 0; i < lines; ++i) {
    std::snprintf(line, sizeof line, "G1X%.3fY%.3f\n", coordinate(rng), coordinate(rng));
    out << line;
  }
  return path;
}

struct Run {
  drivers::StreamSummary summary;
  sim::GrblSimStats stats;
  double thread_cpu_s = 0.0;
};

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

Expected<Run> stream(sim::GrblSimOptions sim_options, const drivers::GrblStreamOptions& options,
                     const std::filesystem::path& program, drivers::ControlInbox* inbox = nullptr) {
  SUBFEED_TRY_ASSIGN(auto pty, sim::Pty::open());
  sim_options.record_executed = false;
  sim_options.boot_time = 5ms;
  sim::GrblSim simulator(std::make_unique<sim::Pty>(std::move(pty)), sim_options);
  simulator.start();
  SUBFEED_TRY_ASSIGN(auto port, drivers::SerialPort::open(simulator.address(), {}));
  SUBFEED_TRY_ASSIGN(auto source, drivers::GcodeSource::open(program, {}));
  Quiet quiet;
  const double cpu_before = thread_cpu_seconds();
  auto summary = drivers::stream_grbl(port, source, options, inbox, quiet);
  const double cpu = thread_cpu_seconds() - cpu_before;
  simulator.stop();
  Run run{summary.value_or(drivers::StreamSummary{}), simulator.stats(), cpu};
  if (!summary && summary.error().code != ErrorCode::machine_fault &&
      summary.error().code != ErrorCode::stopped) {
    return std::unexpected(summary.error());
  }
  return run;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) {
    return 0.0;
  }
  std::ranges::sort(values);
  return values[static_cast<std::size_t>(p * static_cast<double>(values.size() - 1))];
}

// One byte from the sender's serial port to the simulator's side of the pty.
std::vector<double> pty_one_way_ms(int samples) {
  auto pty = sim::Pty::open().value();
  auto port = drivers::SerialPort::open(pty.slave_path(), {}).value();
  std::vector<double> ms;
  char byte = '?';
  char got[8];
  for (int i = 0; i < samples; ++i) {
    const auto start = Clock::now();
    (void)port.write(std::span<const char>(&byte, 1), 100ms);
    while (pty.read(got, 100ms).value_or(0) == 0) {
    }
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    std::this_thread::sleep_for(1ms);
  }
  return ms;
}

sim::GrblSimOptions machine(int baud, double speed) {
  sim::GrblSimOptions o;
  o.baud = baud;
  o.motion.speed = speed;
  return o;
}

void link_use() {
  const auto program = write_program(1500, 1);
  drivers::GrblStreamOptions counting;
  auto waiting = counting;
  waiting.send_and_wait = true;
  const auto a = stream(machine(115200, 1e6), counting, program).value();
  const auto b = stream(machine(115200, 1e6), waiting, program).value();
  const double wire = 115200.0 / 10.0;
  bench::report({"link use, character counting", 100.0 * a.summary.bytes / a.summary.seconds / wire,
                 "% of wire", "send-and-wait", 100.0 * b.summary.bytes / b.summary.seconds / wire});
}

void cpu_per_line() {
  const auto program = write_program(200'000, 2);
  const auto run = stream(machine(0, 1e9), {}, program).value();
  auto source = drivers::GcodeSource::open(program, {}).value();
  const double before = thread_cpu_seconds();
  const auto scan = source.scan().value();
  const double scan_cpu = thread_cpu_seconds() - before;
  bench::report({"host CPU per streamed line",
                 1e6 * run.thread_cpu_s / static_cast<double>(run.summary.lines), "us",
                 "read+prepare line only", 1e6 * scan_cpu / static_cast<double>(scan.lines_to_send),
                 false});
}

void reaction(const std::vector<double>& one_way) {
  const auto program = write_program(60, 3);
  std::vector<double> reactions;
  for (int i = 0; i < 100; ++i) {
    auto o = machine(0, 1e6);
    o.faults.error_on_line = 30;
    const auto run = stream(o, {}, program).value();
    reactions.insert(reactions.end(), run.stats.error_to_hold_ms.begin(),
                     run.stats.error_to_hold_ms.end());
  }
  bench::report({"error:N -> '!' on the wire, p99", percentile(reactions, 0.99), "ms",
                 "pty one-way byte, p99", percentile(one_way, 0.99), false});
  bench::report({"error:N -> '!' on the wire, p50", percentile(reactions, 0.5), "ms",
                 "pty one-way byte, p50", percentile(one_way, 0.5), false});
}

void realtime_latency(const std::vector<double>& one_way) {
  const auto program = write_program(400, 4); // ~130 mm moves at 3000 mm/min: the queue stays full
  auto inbox = drivers::ControlInbox::create().value();
  std::vector<Clock::time_point> pushed;
  std::jthread pusher([&](const std::stop_token& stop) {
    std::this_thread::sleep_for(500ms);
    for (int i = 0; i < 100 && !stop.stop_requested(); ++i) {
      pushed.push_back(Clock::now());
      inbox->push({drivers::ControlCommand::Kind::realtime,
                   i % 2 == 0 ? drivers::grbl_realtime::feed_plus_1
                              : drivers::grbl_realtime::feed_minus_1});
      std::this_thread::sleep_for(10ms);
    }
    inbox->push({drivers::ControlCommand::Kind::stop, 0});
  });
  const auto run = stream(machine(115200, 1.0), {}, program, inbox.get());
  pusher.join();
  std::vector<double> latency;
  if (run) {
    for (std::size_t i = 0; i < std::min(pushed.size(), run->stats.override_times.size()); ++i) {
      latency.push_back(
          std::chrono::duration<double, std::milli>(run->stats.override_times[i] - pushed[i])
              .count());
    }
  }
  bench::report({"realtime byte, full queue, p99", percentile(latency, 0.99), "ms",
                 "pty one-way byte, p99", percentile(one_way, 0.99), false});
}

void memory() {
  const char* env = std::getenv("SUBFEED_BENCH_LINES");
  const long lines = env != nullptr ? std::atol(env) : 10'000'000L;
  const auto small = write_program(100'000, 5);
  (void)stream(machine(0, 1e9), {}, small).value();
  const double baseline = bench::peak_rss_mib();
  std::filesystem::remove(small);
  const auto big = write_program(lines, 6);
  const auto run = stream(machine(0, 1e9), {}, big).value();
  std::filesystem::remove(big);
  bench::report({"peak RSS, " + std::to_string(lines) + " lines", bench::peak_rss_mib(), "MiB",
                 "peak RSS, 100000 lines", baseline, false});
  std::printf("  (%ld lines in %.1f s, %.0f lines/s, no overrun: %s)\n", run.summary.lines,
              run.summary.seconds, run.summary.lines / run.summary.seconds,
              run.stats.overrun_bytes == 0 ? "yes" : "NO");
}

} // namespace

int main() {
  const auto one_way = pty_one_way_ms(500);
  link_use();
  cpu_per_line();
  reaction(one_way);
  realtime_latency(one_way);
  memory();
}
