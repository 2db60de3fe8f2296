#pragma once
// Turns SIGINT/SIGTERM (through a signalfd, so no handler and no global flag) and, on an
// interactive terminal, single keys into commands for a running stream:
//   Ctrl-C, q      stop safely (feed hold, wait, reset)
//   ! or space     feed hold          ~ or r   resume
//   + / -          feed override +10% / -10%      0   feed override 100%
// The terminal is put in single-key mode and restored when the thread ends. Signals must be
// blocked (block_stop_signals) before any thread is started.

#include "base/unique_fd.hpp"
#include "drivers/control_inbox.hpp"

#include <optional>
#include <termios.h>
#include <thread>

namespace subfeed::job {

// Blocks SIGINT and SIGTERM in the calling thread and every thread it starts afterwards.
void block_stop_signals();

class ControlThread {
public:
  ControlThread(drivers::ControlInbox& inbox, bool keyboard);
  ControlThread(const ControlThread&) = delete;
  ControlThread& operator=(const ControlThread&) = delete;
  ~ControlThread();

private:
  void run(drivers::ControlInbox& inbox, bool keyboard);

  UniqueFd signal_fd_;
  UniqueFd quit_fd_;
  std::optional<termios> saved_terminal_;
  std::thread thread_;
};

} // namespace subfeed::job
