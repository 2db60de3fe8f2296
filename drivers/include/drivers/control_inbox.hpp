#pragma once
// Commands for a running stream from other threads: a signal watcher, the keyboard, a
// test. The streamer waits on fd() together with its link, so a command is acted on the
// moment it arrives, not at the next poll tick. Realtime bytes pass straight to the wire;
// they never enter the counted line queue.

#include "base/error.hpp"
#include "base/unique_fd.hpp"

#include <deque>
#include <memory>
#include <mutex>
#include <vector>

namespace subfeed::drivers {

struct ControlCommand {
  enum class Kind {
    realtime, // send `byte` at once (feed hold, resume, overrides, status)
    stop,     // stop safely: feed hold, wait until stopped, reset; the job ends as stopped
  };
  Kind kind = Kind::realtime;
  unsigned char byte = 0;
};

class ControlInbox {
public:
  [[nodiscard]] static Expected<std::unique_ptr<ControlInbox>> create();
  void push(ControlCommand command);
  [[nodiscard]] std::vector<ControlCommand> take();
  [[nodiscard]] int fd() const { return event_fd_.get(); }

private:
  explicit ControlInbox(int event_fd) : event_fd_(event_fd) {}

  UniqueFd event_fd_;
  std::mutex mutex_;
  std::deque<ControlCommand> commands_;
};

// GRBL 1.1 realtime command bytes (docs/PROTOCOLS.md).
namespace grbl_realtime {
inline constexpr unsigned char status = '?';
inline constexpr unsigned char feed_hold = '!';
inline constexpr unsigned char cycle_start = '~';
inline constexpr unsigned char soft_reset = 0x18;
inline constexpr unsigned char feed_100 = 0x90;
inline constexpr unsigned char feed_plus_10 = 0x91;
inline constexpr unsigned char feed_minus_10 = 0x92;
inline constexpr unsigned char feed_plus_1 = 0x93;
inline constexpr unsigned char feed_minus_1 = 0x94;
inline constexpr unsigned char rapid_100 = 0x95;
inline constexpr unsigned char rapid_50 = 0x96;
inline constexpr unsigned char rapid_25 = 0x97;
inline constexpr unsigned char spindle_100 = 0x99;
inline constexpr unsigned char spindle_plus_10 = 0x9A;
inline constexpr unsigned char spindle_minus_10 = 0x9B;
} // namespace grbl_realtime

} // namespace subfeed::drivers
