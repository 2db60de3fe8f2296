#pragma once
// A TCP endpoint for the simulator, as grblHAL's Ethernet stream or a serial-to-TCP server
// offers one: listens on a loopback or given address, serves one connection at a time and
// accepts the next when the sender goes away.

#include "base/unique_fd.hpp"
#include "sim/byte_channel.hpp"

namespace subfeed::sim {

class TcpListener final : public ByteChannel {
public:
  // `port` 0 picks a free port; address() then tells which.
  [[nodiscard]] static Expected<TcpListener> open(const std::string& host, int port);

  [[nodiscard]] Expected<std::size_t> read(std::span<char> buffer,
                                           std::chrono::milliseconds timeout) override;
  [[nodiscard]] Expected<void> write_all(std::span<const char> bytes) override;
  void close() noexcept override {
    peer_.reset();
    listen_.reset();
  }
  [[nodiscard]] std::string address() const override { return address_; }
  [[nodiscard]] bool connected() const override { return peer_.valid(); }
  [[nodiscard]] std::size_t unread() const override;

private:
  TcpListener(int listen_fd, std::string address)
      : listen_(listen_fd), address_(std::move(address)) {}

  UniqueFd listen_;
  UniqueFd peer_;
  std::string address_;
};

} // namespace subfeed::sim
