#include "support/grbl_fixture.hpp"

#include "drivers/gcode_source.hpp"
#include "drivers/journal.hpp"
#include "sim/pty.hpp"

#include <cstring>
#include <random>
#include <sstream>

namespace subfeed::testing {

GrblBench::GrblBench(sim::GrblSimOptions options) {
  auto pty = sim::Pty::open().value();
  options.boot_time = std::chrono::milliseconds(5);
  options.record_executed = true;
  sim = std::make_unique<sim::GrblSim>(std::make_unique<sim::Pty>(std::move(pty)), options);
  sim->start();
  port = std::make_unique<drivers::SerialPort>(
      drivers::SerialPort::open(sim->address(), drivers::SerialOptions{}).value());
}

drivers::GrblStreamOptions GrblBench::fast_options() {
  drivers::GrblStreamOptions o;
  o.connect_timeout = std::chrono::milliseconds(2000);
  o.silence_timeout = std::chrono::milliseconds(2000);
  o.hold_timeout = std::chrono::milliseconds(3000);
  o.status_hz = 20.0;
  return o;
}

Expected<drivers::StreamSummary> GrblBench::stream(const std::string& program,
                                                   const drivers::GrblStreamOptions& options,
                                                   drivers::ControlInbox* inbox) {
  const auto file = dir.write("job.nc", program);
  SUBFEED_TRY_ASSIGN(auto source, drivers::GcodeSource::open(file, {}));
  return drivers::stream_grbl(*port, source, options, inbox, observer);
}

Expected<drivers::StreamSummary>
GrblBench::stream_journaled(const std::string& program, const std::filesystem::path& journal,
                            const drivers::GrblStreamOptions& options) {
  const auto file = dir.write("job.nc", program);
  SUBFEED_TRY_ASSIGN(auto source, drivers::GcodeSource::open(file, {}));
  SUBFEED_TRY_ASSIGN(auto log, drivers::Journal::open(journal));
  drivers::JournaledObserver journaled(observer, log);
  log.start("grbl", file.string(), port->name());
  auto outcome = drivers::stream_grbl(*port, source, options, nullptr, journaled);
  log.end(outcome);
  return outcome;
}

std::vector<std::string> stripped_lines(const std::string& program) {
  std::vector<std::string> lines;
  std::istringstream in(program);
  std::string raw;
  while (std::getline(in, raw)) {
    const auto prepared = drivers::prepare_line(raw, {256, false}, {}).value();
    if (!prepared.text.empty()) {
      lines.push_back(prepared.text);
    }
  }
  return lines;
}

std::string random_program(int count, int max_length, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(-2.0, 2.0);
  std::uniform_int_distribution<int> pad(0, 1 << 20);
  std::string program = "G21G90G94\nG1F30000\n";
  double x = 0, y = 0;
  for (int i = 0; i < count; ++i) {
    x += step(rng);
    y += step(rng);
    char xs[32], ys[32];
    std::snprintf(xs, sizeof xs, "%.3f", x);
    std::snprintf(ys, sizeof ys, "%.3f", y);
    // Trailing zeros on X spread the lengths up to the limit without changing the move.
    const int room = max_length - static_cast<int>(std::string("G1X").size() + std::strlen(xs) + 1 +
                                                   std::strlen(ys));
    const int zeros = room > 0 ? pad(rng) % (room + 1) : 0;
    program += "G1X" + std::string(xs) + std::string(static_cast<std::size_t>(zeros), '0') + "Y" +
               ys + "\n";
  }
  return program;
}

} // namespace subfeed::testing
