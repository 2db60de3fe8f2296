#include "drivers/serial_port.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>
#include <utility>

namespace subfeed::drivers {

namespace {

struct BaudCode {
  int baud;
  speed_t code;
};

constexpr std::array<BaudCode, 13> baud_codes{{{300, B300},
                                               {600, B600},
                                               {1200, B1200},
                                               {2400, B2400},
                                               {4800, B4800},
                                               {9600, B9600},
                                               {19200, B19200},
                                               {38400, B38400},
                                               {57600, B57600},
                                               {115200, B115200},
                                               {230400, B230400},
                                               {460800, B460800},
                                               {921600, B921600}}};

std::string os_error() {
  return std::strerror(errno);
}

bool set_framing(termios& tio, const SerialOptions& o) {
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  tio.c_cflag |= (o.data_bits == 7 ? CS7 : CS8) | CLOCAL | CREAD;
  if (o.parity != SerialParity::none) {
    tio.c_cflag |= PARENB | (o.parity == SerialParity::odd ? PARODD : 0);
  }
  if (o.stop_bits == 2) {
    tio.c_cflag |= CSTOPB;
  }
  const bool software = o.flow == SerialFlow::xon_xoff || o.flow == SerialFlow::both;
  const bool hardware = o.flow == SerialFlow::rts_cts || o.flow == SerialFlow::both;
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  if (software) {
    tio.c_iflag |= IXON | IXOFF;
  }
  if (hardware) {
    tio.c_cflag |= CRTSCTS;
  }
  return (o.data_bits == 7 || o.data_bits == 8) && (o.stop_bits == 1 || o.stop_bits == 2);
}

} // namespace

Expected<SerialPort> SerialPort::open(const std::string& path, const SerialOptions& options) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return fail(ErrorCode::machine_fault, "cannot open serial port: " + os_error(), {path, 0, {}});
  }
  SerialPort port(fd, path);
  if (!::isatty(fd)) {
    return fail(ErrorCode::machine_fault, "not a serial port (not a tty)", {path, 0, {}});
  }
  // TIOCEXCL keeps other programs out, but not root; the advisory lock is honoured by
  // cooperating senders whoever runs them. Two senders on one machine must never mix.
  if (::ioctl(fd, TIOCEXCL) != 0) {
    return port.failure("cannot get exclusive access");
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    return fail(ErrorCode::machine_fault, "port is in use by another program", {path, 0, {}});
  }
  const auto baud = std::ranges::find(baud_codes, options.baud, &BaudCode::baud);
  if (baud == baud_codes.end()) {
    return fail(ErrorCode::bad_input, "unsupported baud rate " + std::to_string(options.baud),
                {path, 0, "baud"});
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    return port.failure("cannot read port settings");
  }
  ::cfmakeraw(&tio);
  if (!set_framing(tio, options)) {
    return fail(ErrorCode::bad_input, "unsupported framing", {path, 0, {}});
  }
  ::cfsetispeed(&tio, baud->code);
  ::cfsetospeed(&tio, baud->code);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    return port.failure("cannot configure " + std::to_string(options.baud) + " baud");
  }
  ::tcflush(fd, TCIOFLUSH); // nothing stale from an earlier session
  return port;
}

std::unexpected<Error> SerialPort::failure(const std::string& what) const {
  return fail(ErrorCode::machine_fault, what + ": " + os_error(), {path_, 0, {}});
}

// True when `events` are ready; false on timeout. A hang-up or error condition is reported
// as the port having vanished.
Expected<bool> SerialPort::wait(short events, std::chrono::milliseconds timeout) const {
  pollfd p{fd_.get(), events, 0};
  const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (ready < 0) {
    return errno == EINTR ? Expected<bool>(false) : failure("poll failed");
  }
  if (ready == 0) {
    return false;
  }
  if ((p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0 && (p.revents & POLLIN) == 0) {
    return fail(ErrorCode::machine_fault, "port vanished (hang-up)", {path_, 0, {}});
  }
  return true;
}

Expected<std::size_t> SerialPort::read(std::span<char> buffer, std::chrono::milliseconds timeout) {
  SUBFEED_TRY_ASSIGN(const bool ready, wait(POLLIN, timeout));
  if (!ready) {
    return 0;
  }
  const ssize_t n = ::read(fd_.get(), buffer.data(), buffer.size());
  if (n > 0) {
    return static_cast<std::size_t>(n);
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
    return 0;
  }
  // Readable yet nothing to read (EOF) or EIO: the device is gone.
  return fail(ErrorCode::machine_fault,
              std::string("port vanished") + (n < 0 ? ": " + os_error() : std::string()),
              {path_, 0, {}});
}

Expected<std::size_t> SerialPort::write(std::span<const char> bytes,
                                        std::chrono::milliseconds timeout) {
  SUBFEED_TRY_ASSIGN(const bool ready, wait(POLLOUT, timeout));
  if (!ready) {
    return 0;
  }
  const ssize_t n = ::write(fd_.get(), bytes.data(), bytes.size());
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) {
      return 0;
    }
    return failure("write failed");
  }
  return static_cast<std::size_t>(n);
}

Expected<void> SerialPort::drain() {
  if (::tcdrain(fd_.get()) != 0) {
    return failure("drain failed");
  }
  return {};
}

} // namespace subfeed::drivers
