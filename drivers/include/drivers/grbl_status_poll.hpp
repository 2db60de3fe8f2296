#pragma once
// Asking a GRBL-style controller where its machine stands, outside a stream: a handshake
// that reads its state, status polls ('?', a realtime byte, at most 5 a second as GRBL
// wants), waiting until the machine stands still, and waiting for a report that carries the
// work offset. What `resume` needs before it can choose where a program continues.

#include "base/error.hpp"
#include "drivers/grbl_reply.hpp"
#include "drivers/transport.hpp"

#include <chrono>
#include <functional>
#include <optional>
#include <string>

namespace subfeed::drivers {

// Whether the state says the machine may still be moving (Run, Jog, Home, or a hold that
// is still decelerating).
[[nodiscard]] bool machine_moving(const StatusReport& status);

// Connects as a stream would (welcome, wake-up, $I) and returns the state and machine
// position the controller reports; an error when it reports no position.
[[nodiscard]] Expected<StatusReport> probe_status(Transport& link,
                                                  std::chrono::milliseconds connect_timeout);

// Reads status reports through one transport; bytes of a half-read line are kept between
// polls.
class StatusPoller {
public:
  explicit StatusPoller(Transport& link) : link_(link) {}

  // Sends '?' and returns the newest report that came back within 200 ms; other lines are
  // dropped.
  [[nodiscard]] Expected<std::optional<StatusReport>> poll();

  // Polls until the machine stands still. `still_moving` is told once, with the state, when
  // the first report says it moves. No report within `silent`: returns (the handshake that
  // follows says why); still moving after `limit`: a machine fault.
  [[nodiscard]] Expected<void>
  wait_until_still(std::chrono::milliseconds silent, std::chrono::minutes limit,
                   const std::function<void(const std::string& state)>& still_moving);

  // Polls until a report says where the work offset is (GRBL adds WCO to one report in 10
  // to 30), at most `polls` times; then the newest report as it is.
  [[nodiscard]] Expected<StatusReport> with_work_offset(StatusReport status, int polls);

private:
  Transport& link_;
  std::string pending_;
};

} // namespace subfeed::drivers
