#pragma once
// A simulated GRBL on a real pty and the real serial port talking to it, for streaming
// tests: what the sender did is read back from the simulator's statistics.

#include "drivers/grbl_streamer.hpp"
#include "drivers/serial_port.hpp"
#include "sim/grbl_sim.hpp"
#include "support/temp_dir.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace subfeed::testing {

// Records everything a stream reports.
class RecordingObserver final : public drivers::StreamObserver {
public:
  void connected(const drivers::ControllerInfo& i) override { info = i; }
  void progress(const drivers::StreamProgress& p) override {
    last = p;
    ++progress_calls;
  }
  void message(std::string_view line) override { messages.emplace_back(line); }
  void line_error(const drivers::LineError& e) override { errors.push_back(e); }
  void phase(std::string_view name) override { phases.emplace_back(name); }

  drivers::ControllerInfo info;
  drivers::StreamProgress last;
  long progress_calls = 0;
  std::vector<std::string> messages;
  std::vector<drivers::LineError> errors;
  std::vector<std::string> phases;
};

struct GrblBench {
  explicit GrblBench(sim::GrblSimOptions options);

  // Streams `program` (written to a temp file) with `options`; `inbox` may be null.
  Expected<drivers::StreamSummary>
  stream(const std::string& program, const drivers::GrblStreamOptions& options = fast_options(),
         drivers::ControlInbox* inbox = nullptr);

  // As stream(), every report also written to a real journal at `journal`.
  Expected<drivers::StreamSummary>
  stream_journaled(const std::string& program, const std::filesystem::path& journal,
                   const drivers::GrblStreamOptions& options = fast_options());

  // Options with short timeouts so that failing tests fail fast.
  static drivers::GrblStreamOptions fast_options();

  TempDir dir;
  std::unique_ptr<sim::GrblSim> sim;
  std::unique_ptr<drivers::SerialPort> port;
  RecordingObserver observer;
};

// Non-blank lines of `program` as the sender strips them.
std::vector<std::string> stripped_lines(const std::string& program);

// A program of `count` random feed moves of random length up to `max_length` characters.
std::string random_program(int count, int max_length, unsigned seed);

} // namespace subfeed::testing
