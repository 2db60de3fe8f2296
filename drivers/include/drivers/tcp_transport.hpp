#pragma once
// A TCP connection to a controller: grblHAL's Ethernet stream or a serial-to-TCP server.
// Connecting has a timeout; Nagle is off so that single realtime bytes go out at once.

#include "drivers/transport.hpp"

#include <memory>

namespace subfeed::drivers {

class TcpTransport final : public Transport {
public:
  // `endpoint` is HOST:PORT.
  [[nodiscard]] static Expected<TcpTransport> connect(const std::string& endpoint,
                                                      std::chrono::milliseconds timeout);

  TcpTransport(TcpTransport&&) noexcept;
  TcpTransport& operator=(TcpTransport&&) noexcept;
  ~TcpTransport() override;

  [[nodiscard]] Expected<std::size_t> read(std::span<char> buffer,
                                           std::chrono::milliseconds timeout) override;
  [[nodiscard]] Expected<std::size_t> write(std::span<const char> bytes,
                                            std::chrono::milliseconds timeout) override;
  [[nodiscard]] int poll_fd() const override;
  [[nodiscard]] const std::string& name() const override { return name_; }

private:
  struct Socket;
  TcpTransport(std::unique_ptr<Socket> socket, std::string name);
  [[nodiscard]] Expected<bool> wait(short events, std::chrono::milliseconds timeout) const;

  std::unique_ptr<Socket> socket_;
  std::string name_;
};

} // namespace subfeed::drivers
