#include "drivers/grbl_status_poll.hpp"

#include "drivers/grbl_streamer.hpp"
#include "drivers/live_program.hpp"

#include <utility>

namespace subfeed::drivers {

namespace {

// What the controller says once connected: state and machine position.
class StatusProbe final : public StreamObserver {
public:
  void progress(const StreamProgress& p) override {
    if (p.status) {
      status = p.status;
    }
  }
  std::optional<StatusReport> status;
};

} // namespace

bool machine_moving(const StatusReport& status) {
  return status.state == "Run" || status.state == "Jog" || status.state == "Home" ||
         (status.state == "Hold" && status.substate != 0);
}

Expected<StatusReport> probe_status(Transport& link, std::chrono::milliseconds connect_timeout) {
  ProgramQueue nothing(1);
  nothing.close();
  LiveGcode empty("(status)", nothing);
  GrblStreamOptions options;
  options.connect_timeout = connect_timeout;
  StatusProbe observer;
  SUBFEED_TRY(stream_grbl(link, empty, options, nullptr, observer));
  if (!observer.status || observer.status->machine_position.size() < 3) {
    return fail(ErrorCode::machine_fault, "the controller reported no position", {});
  }
  return *observer.status;
}

Expected<std::optional<StatusReport>> StatusPoller::poll() {
  SUBFEED_TRY(write_all(link_, std::span<const char>("?", 1), std::chrono::milliseconds(1000)));
  char buffer[512];
  SUBFEED_TRY_ASSIGN(const auto got,
                     link_.read(std::span<char>(buffer), std::chrono::milliseconds(200)));
  pending_.append(buffer, got);
  std::optional<StatusReport> newest;
  for (auto end = pending_.find('\n'); end != std::string::npos; end = pending_.find('\n')) {
    auto line = std::string_view(pending_).substr(0, end);
    if (line.ends_with('\r')) {
      line.remove_suffix(1);
    }
    if (auto report = parse_status(line)) {
      newest = std::move(report);
    }
    pending_.erase(0, end + 1);
  }
  return newest;
}

Expected<void>
StatusPoller::wait_until_still(std::chrono::milliseconds silent, std::chrono::minutes limit,
                               const std::function<void(const std::string& state)>& still_moving) {
  const auto start = std::chrono::steady_clock::now();
  bool told = false;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto report, poll());
    const auto waited = std::chrono::steady_clock::now() - start;
    if (report && !machine_moving(*report)) {
      return {};
    }
    if (report && !std::exchange(told, true)) {
      still_moving(report->state);
    }
    if (!told && waited > silent) {
      return {};
    }
    if (waited > limit) {
      return fail(ErrorCode::machine_fault,
                  "the machine did not stop within " + std::to_string(limit.count()) + " minutes",
                  {});
    }
  }
}

Expected<StatusReport> StatusPoller::with_work_offset(StatusReport status, int polls) {
  for (int i = 0; i < polls && !status.work_position && !status.work_offset; ++i) {
    SUBFEED_TRY_ASSIGN(const auto report, poll());
    if (report) {
      status = *report;
    }
  }
  return status;
}

} // namespace subfeed::drivers
