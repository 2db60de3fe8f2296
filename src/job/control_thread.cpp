#include "job/control_thread.hpp"

#include <csignal>
#include <cstdint>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <unistd.h>

namespace subfeed::job {

namespace {

sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

std::optional<drivers::ControlCommand> key_command(char key) {
  using drivers::ControlCommand;
  namespace rt = drivers::grbl_realtime;
  switch (key) {
  case 0x03: // Ctrl-C arrives as a key in single-key mode
  case 'q':
    return ControlCommand{ControlCommand::Kind::stop, 0};
  case '!':
  case ' ':
    return ControlCommand{ControlCommand::Kind::realtime, rt::feed_hold};
  case '~':
  case 'r':
    return ControlCommand{ControlCommand::Kind::realtime, rt::cycle_start};
  case '+':
    return ControlCommand{ControlCommand::Kind::realtime, rt::feed_plus_10};
  case '-':
    return ControlCommand{ControlCommand::Kind::realtime, rt::feed_minus_10};
  case '0':
    return ControlCommand{ControlCommand::Kind::realtime, rt::feed_100};
  default:
    return std::nullopt;
  }
}

} // namespace

void block_stop_signals() {
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

ControlThread::ControlThread(drivers::ControlInbox& inbox, bool keyboard) {
  const sigset_t set = stop_signals();
  signal_fd_.reset(::signalfd(-1, &set, SFD_CLOEXEC));
  quit_fd_.reset(::eventfd(0, EFD_CLOEXEC));
  if (keyboard && ::isatty(STDIN_FILENO) != 0) {
    termios tio{};
    if (::tcgetattr(STDIN_FILENO, &tio) == 0) {
      saved_terminal_ = tio;
      tio.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO | ISIG);
      tio.c_cc[VMIN] = 1;
      tio.c_cc[VTIME] = 0;
      ::tcsetattr(STDIN_FILENO, TCSANOW, &tio);
    }
  }
  thread_ = std::thread([this, &inbox] { run(inbox, saved_terminal_.has_value()); });
}

ControlThread::~ControlThread() {
  const std::uint64_t one = 1;
  (void)!::write(quit_fd_.get(), &one, sizeof one);
  thread_.join();
  if (saved_terminal_) {
    ::tcsetattr(STDIN_FILENO, TCSANOW, &*saved_terminal_);
  }
}

void ControlThread::run(drivers::ControlInbox& inbox, bool keyboard) {
  while (true) {
    pollfd fds[3] = {{quit_fd_.get(), POLLIN, 0},
                     {signal_fd_.get(), POLLIN, 0},
                     {keyboard ? STDIN_FILENO : -1, POLLIN, 0}};
    if (::poll(fds, 3, -1) < 0) {
      continue;
    }
    if (fds[0].revents != 0) {
      return;
    }
    if (fds[1].revents != 0) {
      signalfd_siginfo info{};
      if (::read(signal_fd_.get(), &info, sizeof info) == sizeof info) {
        inbox.push({drivers::ControlCommand::Kind::stop, 0});
      }
    }
    if (fds[2].revents != 0) {
      char key = 0;
      if (::read(STDIN_FILENO, &key, 1) == 1) {
        if (const auto command = key_command(key)) {
          inbox.push(*command);
        }
      }
    }
  }
}

} // namespace subfeed::job
