// Fanuc-style DNC figures, each beside a baseline from the same run:
//   link use at 19200 baud with a control that drains fast   vs the wire's capacity
//   worst characters after XOFF at 9600 7E2                  vs the control's tolerance (10)
//   peak memory sending 10 million blocks                    vs peak memory after 100,000
// SUBFEED_BENCH_BLOCKS overrides the 10 million.

#include "bench_harness.hpp"

#include "drivers/fanuc_program.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "sim/fanuc_sim.hpp"
#include "sim/pty.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

namespace {

using namespace subfeed;
using namespace std::chrono_literals;

class Quiet final : public drivers::StreamObserver {};

std::filesystem::path write_program(long blocks) {
  const auto path =
      std::filesystem::temp_directory_path() / ("subfeed-dnc-" + std::to_string(blocks) + ".nc");
  std::ofstream out(path);
  out << "G21 G90 G17\nG01 F600\n";
  for (long i = 0; i < blocks; ++i) {
    out << 'X' << i % 97 << '.' << i % 10 << " Y" << i % 89 << '\n';
  }
  return path;
}

struct Run {
  drivers::StreamSummary summary;
  sim::FanucSimStats stats;
};

// `pacing` is the rate the sender times its characters by; the pty itself has no speed.
Run send(sim::FanucSimOptions control, drivers::SerialOptions pacing,
         const std::filesystem::path& program) {
  sim::FanucSim simulator(std::make_unique<sim::Pty>(sim::Pty::open().value()), control);
  simulator.start();
  drivers::SerialOptions port_framing = pacing;
  port_framing.baud = 115200; // any rate the port accepts: a pty ignores it
  auto port =
      drivers::SerialPort::open(simulator.address(), drivers::dnc_port_options(port_framing))
          .value();
  auto file = drivers::FanucProgram::open(program).value();
  drivers::FanucStreamOptions options;
  options.serial = pacing;
  Quiet quiet;
  auto summary = drivers::stream_fanuc(port, file, options, nullptr, quiet).value();
  std::this_thread::sleep_for(200ms);
  simulator.stop();
  return {summary, simulator.stats()};
}

} // namespace

int main() {
  {
    const auto program = write_program(1000);
    sim::FanucSimOptions control;
    control.baud = 19200;
    control.data_bits = 8;
    control.parity = 'N';
    control.stop_bits = 1;
    control.motion.speed = 1e6;
    const auto run =
        send(control, {19200, 8, drivers::SerialParity::none, 1, drivers::SerialFlow::xon_xoff},
             program);
    bench::report({"DNC link use, 19200 8N1", run.summary.bytes / run.summary.seconds, "chars/s",
                   "wire capacity", 19200.0 / 10.0});
  }
  {
    const auto program = write_program(400);
    sim::FanucSimOptions control;
    control.look_ahead_blocks = 2;
    control.buffer = 64;
    control.high_water = 40;
    control.low_water = 16;
    control.motion.speed = 20.0;
    const auto run = send(
        control, {9600, 7, drivers::SerialParity::even, 2, drivers::SerialFlow::xon_xoff}, program);
    bench::report({"worst chars after XOFF, 9600 7E2",
                   static_cast<double>(run.stats.max_after_xoff), "chars", "control's tolerance",
                   10.0, false});
    std::printf("  (%ld XOFF, %ld blocks, alarm: %s)\n", run.stats.xoff_sent,
                run.stats.executed_count,
                run.stats.alarm.empty() ? "none" : run.stats.alarm.c_str());
  }
  {
    const char* env = std::getenv("SUBFEED_BENCH_BLOCKS");
    const long blocks = env != nullptr ? std::atol(env) : 10'000'000L;
    sim::FanucSimOptions control;
    control.baud = 0;
    control.buffer = 65536;
    control.high_water = 32768;
    control.low_water = 8192;
    control.overrun_tolerance = 4096; // the sender writes hundreds of characters at a time here
    control.motion.speed = 1e9;
    control.data_bits = 8;
    control.parity = 'N';
    control.stop_bits = 1;
    const drivers::SerialOptions fast{4000000, 8, drivers::SerialParity::none, 1,
                                      drivers::SerialFlow::xon_xoff};
    const auto small = write_program(100'000);
    (void)send(control, fast, small);
    const double baseline = bench::peak_rss_mib();
    std::filesystem::remove(small);
    const auto big = write_program(blocks);
    const auto run = send(control, fast, big);
    std::filesystem::remove(big);
    bench::report({"peak RSS, " + std::to_string(blocks) + " blocks", bench::peak_rss_mib(), "MiB",
                   "peak RSS, 100000 blocks", baseline, false});
    std::printf("  (%ld blocks in %.1f s, delivered %ld, alarm: %s)\n", run.summary.lines,
                run.summary.seconds, run.stats.executed_count,
                run.stats.alarm.empty() ? "none" : run.stats.alarm.c_str());
  }
}
