#pragma once
// A serial port on any tty path: real UART, USB adapter or pty, opened through POSIX termios
// in raw mode with exclusive access (a second sender on the same machine is refused). The
// port is closed when the object dies. Reads return what has arrived (at least one byte) or
// zero bytes after the timeout; writes return how many bytes the OS took. Every failure,
// including a port that vanished (USB unplugged, far side of a pty closed), is an Error with
// code machine_fault naming the port.
//
// Why not libserialport here: it refuses ptys (it needs a sysfs entry a pty lacks), and a
// simulated controller must be reached through exactly the code path of a real port.

#include "base/error.hpp"
#include "base/unique_fd.hpp"
#include "drivers/transport.hpp"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace subfeed::drivers {

enum class SerialParity { none, even, odd };
enum class SerialFlow { none, xon_xoff, rts_cts, both };

struct SerialOptions {
  int baud = 115200;
  int data_bits = 8;
  SerialParity parity = SerialParity::none;
  int stop_bits = 1;
  SerialFlow flow = SerialFlow::none;
};

class SerialPort final : public Transport {
public:
  [[nodiscard]] static Expected<SerialPort> open(const std::string& path,
                                                 const SerialOptions& options);

  [[nodiscard]] Expected<std::size_t> read(std::span<char> buffer,
                                           std::chrono::milliseconds timeout);
  [[nodiscard]] Expected<std::size_t> write(std::span<const char> bytes,
                                            std::chrono::milliseconds timeout);
  // Waits until the OS has handed every written byte to the hardware (returns at once on a
  // pty, which has no wire).
  [[nodiscard]] Expected<void> drain();
  [[nodiscard]] int poll_fd() const override { return fd_.get(); }
  [[nodiscard]] const std::string& name() const override { return path_; }

private:
  SerialPort(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  [[nodiscard]] std::unexpected<Error> failure(const std::string& what) const;
  [[nodiscard]] Expected<bool> wait(short events, std::chrono::milliseconds timeout) const;

  UniqueFd fd_; // closing it also ends the exclusive access and the lock
  std::string path_;
};

} // namespace subfeed::drivers
