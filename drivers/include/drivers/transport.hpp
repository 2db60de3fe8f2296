#pragma once
// A byte link to a controller: a serial port or a TCP connection. Reads return what has
// arrived (zero bytes on timeout), writes what the OS took (zero on timeout); a link that
// broke is an Error with code machine_fault. poll_fd() lets a caller wait for input from
// the link and from other sources at once.

#include "base/error.hpp"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace subfeed::drivers {

class Transport {
public:
  virtual ~Transport() = default;
  [[nodiscard]] virtual Expected<std::size_t> read(std::span<char> buffer,
                                                   std::chrono::milliseconds timeout) = 0;
  [[nodiscard]] virtual Expected<std::size_t> write(std::span<const char> bytes,
                                                    std::chrono::milliseconds timeout) = 0;
  [[nodiscard]] virtual int poll_fd() const = 0;
  // The port path or host:port, for messages.
  [[nodiscard]] virtual const std::string& name() const = 0;
};

// Writes every byte or fails: a link that takes nothing for `timeout` is a fault.
[[nodiscard]] Expected<void> write_all(Transport& link, std::span<const char> bytes,
                                       std::chrono::milliseconds timeout);

} // namespace subfeed::drivers
