#pragma once
// A job's journal: append-only, one event a line, each line handed to the OS the moment it
// happens, so that a crash of subfeed itself loses nothing already recorded. Lines are
// "<ms since start> <event> <fields>":
//   start protocol=grbl program=job.nc link=/dev/ttyUSB0
//   sent line=14 bytes=23          a line (GRBL) or block (DNC) of the program went out
//   answered line=14 ok            GRBL: the controller took it (or error:N)
//   event xoff | xon | alarm ALARM:1 | reset | status <Idle|...> | phase stream
//   end done | end failed <the error's one line>
// It is what `resume` (to come) reads to find where a job stopped.

#include "base/error.hpp"
#include "base/unique_fd.hpp"
#include "drivers/grbl_streamer.hpp"

#include <chrono>
#include <filesystem>
#include <string_view>

namespace subfeed::drivers {

class Journal {
public:
  [[nodiscard]] static Expected<Journal> open(const std::filesystem::path& path);

  void start(std::string_view protocol, std::string_view program, std::string_view link);
  void sent(long line, long bytes);
  void answered(long line, int error_code); // 0: ok
  void event(std::string_view name, std::string_view detail = {});
  void end(const Expected<StreamSummary>& outcome);

private:
  explicit Journal(int fd) : fd_(fd), start_(std::chrono::steady_clock::now()) {}
  void write_line(std::string_view text);

  UniqueFd fd_;
  std::chrono::steady_clock::time_point start_;
};

// Passes every report to `inner` and records what a resume needs in `journal`.
class JournaledObserver final : public StreamObserver {
public:
  JournaledObserver(StreamObserver& inner, Journal& journal) : inner_(inner), journal_(journal) {}

  void connected(const ControllerInfo& info) override { inner_.connected(info); }
  void progress(const StreamProgress& p) override;
  void message(std::string_view line) override { inner_.message(line); }
  void line_error(const LineError& e) override { inner_.line_error(e); }
  void phase(std::string_view name) override;
  void line_sent(long line, long bytes) override {
    journal_.sent(line, bytes);
    inner_.line_sent(line, bytes);
  }
  void line_answered(long line, int error_code) override {
    journal_.answered(line, error_code);
    inner_.line_answered(line, error_code);
  }
  void link_event(std::string_view name, std::string_view detail) override {
    journal_.event(name, detail);
  }

private:
  StreamObserver& inner_;
  Journal& journal_;
  std::string last_state_;
};

} // namespace subfeed::drivers
