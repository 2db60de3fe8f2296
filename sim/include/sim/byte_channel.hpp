#pragma once
// The simulator's end of a link: the master side of a pty, or a TCP listener with at most
// one accepted connection. A sender may connect, go away and connect again, as with a real
// controller; reads return zero bytes while nobody is connected, and connected() tells.
// Owns its fds.

#include "base/error.hpp"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace subfeed::sim {

class ByteChannel {
public:
  virtual ~ByteChannel() = default;
  [[nodiscard]] virtual Expected<std::size_t> read(std::span<char> buffer,
                                                   std::chrono::milliseconds timeout) = 0;
  [[nodiscard]] virtual Expected<void> write_all(std::span<const char> bytes) = 0;
  [[nodiscard]] virtual bool connected() const = 0;
  // Bytes that have arrived and no read has taken yet: the sender wrote them before
  // anything the simulator writes now can reach it.
  [[nodiscard]] virtual std::size_t unread() const = 0;
  // Drops the link as an unplugged cable would; nothing more is read or written.
  virtual void close() noexcept = 0;
  // What a sender connects to: a tty path or host:port.
  [[nodiscard]] virtual std::string address() const = 0;
};

} // namespace subfeed::sim
