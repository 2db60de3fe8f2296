#pragma once
// A pseudo-terminal pair: the master side, which a simulated controller (or a test) owns,
// and the path of the slave side, which a sender opens like any serial port. The master is
// in raw mode so that bytes pass unchanged (no echo, no CR/LF translation, no XON/XOFF
// interpretation). The master fd is closed when the Pty dies; closing it makes the slave
// side see a hang-up, which is how a vanished port looks to a sender.

#include "base/error.hpp"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace subfeed::sim {

class Pty {
public:
  [[nodiscard]] static Expected<Pty> open();

  Pty(Pty&& other) noexcept;
  Pty& operator=(Pty&& other) noexcept;
  Pty(const Pty&) = delete;
  Pty& operator=(const Pty&) = delete;
  ~Pty();

  [[nodiscard]] int master_fd() const { return master_; }
  [[nodiscard]] const std::string& slave_path() const { return slave_path_; }

  // Bytes that arrived within `timeout`; empty on timeout. An error when the slave side
  // hung up after having been opened, or on an I/O failure.
  [[nodiscard]] Expected<std::size_t> read(std::span<char> buffer,
                                           std::chrono::milliseconds timeout);
  [[nodiscard]] Expected<void> write_all(std::span<const char> bytes);

  // Hangs up: the slave side sees the port vanish.
  void close() noexcept;

private:
  Pty(int master, std::string slave_path) : master_(master), slave_path_(std::move(slave_path)) {}

  int master_ = -1;
  std::string slave_path_;
};

} // namespace subfeed::sim
