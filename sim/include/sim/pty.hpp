#pragma once
// A pseudo-terminal pair: the master side, which a simulated controller (or a test) owns,
// and the path of the slave side, which a sender opens like any serial port. The master is
// in raw mode so that bytes pass unchanged (no echo, no CR/LF translation, no XON/XOFF
// interpretation). The master fd is closed when the Pty dies; closing it makes the slave
// side see a hang-up, which is how a vanished port looks to a sender.

#include "base/error.hpp"
#include "base/unique_fd.hpp"
#include "sim/byte_channel.hpp"

#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace subfeed::sim {

class Pty final : public ByteChannel {
public:
  [[nodiscard]] static Expected<Pty> open();

  [[nodiscard]] int master_fd() const { return master_.get(); }
  [[nodiscard]] const std::string& slave_path() const { return slave_path_; }

  // Bytes that arrived within `timeout`; zero on timeout and while no one has the slave
  // side open. An error only on an I/O failure.
  [[nodiscard]] Expected<std::size_t> read(std::span<char> buffer,
                                           std::chrono::milliseconds timeout) override;
  [[nodiscard]] Expected<void> write_all(std::span<const char> bytes) override;

  // Hangs up: the slave side sees the port vanish.
  void close() noexcept override { master_.reset(); }
  [[nodiscard]] std::string address() const override { return slave_path_; }
  [[nodiscard]] bool connected() const override { return connected_; }
  [[nodiscard]] std::size_t unread() const override;

private:
  Pty(int master, std::string slave_path) : master_(master), slave_path_(std::move(slave_path)) {}

  UniqueFd master_;
  std::string slave_path_;
  bool connected_ = false;
};

} // namespace subfeed::sim
