#include "sim/pty.hpp"

#include "os_failure.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <thread>
#include <unistd.h>
#include <utility>

namespace subfeed::sim {

Expected<Pty> Pty::open() {
  const int fd = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    return os_failure("posix_openpt", "pty");
  }
  Pty pty(fd, {});
  char name[128] = {};
  if (::grantpt(fd) != 0 || ::unlockpt(fd) != 0 || ::ptsname_r(fd, name, sizeof name) != 0) {
    return os_failure("cannot prepare pty", "pty");
  }
  pty.slave_path_ = name;
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    return os_failure("tcgetattr", pty.slave_path_);
  }
  ::cfmakeraw(&tio);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    return os_failure("tcsetattr", pty.slave_path_);
  }
  // A master whose slave was never opened reports no hang-up, so a first connection could
  // not be told from none. Opening and closing the slave once puts it in the hung-up state.
  const int slave = ::open(pty.slave_path_.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) {
    return os_failure("cannot open the slave side", pty.slave_path_);
  }
  ::close(slave);
  return pty;
}

Expected<std::size_t> Pty::read(std::span<char> buffer, std::chrono::milliseconds timeout) {
  if (!master_.valid()) {
    std::this_thread::sleep_for(timeout);
    return 0;
  }
  pollfd p{master_.get(), POLLIN, 0};
  const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (ready < 0) {
    return errno == EINTR ? Expected<std::size_t>(0) : os_failure("poll", slave_path_);
  }
  if (ready == 0) {
    connected_ = true; // no hang-up reported: someone has the slave side open
    return 0;
  }
  if ((p.revents & POLLIN) == 0 && (p.revents & POLLHUP) != 0) {
    // Nobody has the slave open: poll keeps reporting the hang-up, so wait here instead.
    connected_ = false;
    std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(2)));
    return 0;
  }
  connected_ = true;
  const ssize_t n = ::read(master_.get(), buffer.data(), buffer.size());
  if (n < 0) {
    if (errno == EIO || errno == EAGAIN || errno == EINTR) { // EIO: the slave just closed
      connected_ = errno != EIO;
      return 0;
    }
    return os_failure("read", slave_path_);
  }
  return static_cast<std::size_t>(n);
}

std::size_t Pty::unread() const {
  int n = 0;
  return master_.valid() && ::ioctl(master_.get(), FIONREAD, &n) == 0 && n > 0
             ? static_cast<std::size_t>(n)
             : 0;
}

Expected<void> Pty::write_all(std::span<const char> bytes) {
  while (!bytes.empty()) {
    const ssize_t n = master_.valid() ? ::write(master_.get(), bytes.data(), bytes.size()) : -1;
    if (n < 0) {
      if (errno == EINTR) {
        continue;
      }
      if (!master_.valid() || errno == EIO) { // nobody listening: the bytes fall off the wire
        return {};
      }
      return os_failure("write", slave_path_);
    }
    bytes = bytes.subspan(static_cast<std::size_t>(n));
  }
  return {};
}

} // namespace subfeed::sim
