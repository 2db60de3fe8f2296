#include "drivers/tcp_transport.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <poll.h>

namespace subfeed::drivers {

namespace asio = boost::asio;

struct TcpTransport::Socket {
  asio::io_context io;
  asio::ip::tcp::socket socket{io};
};

TcpTransport::TcpTransport(std::unique_ptr<Socket> socket, std::string name)
    : socket_(std::move(socket)), name_(std::move(name)) {}
TcpTransport::TcpTransport(TcpTransport&&) noexcept = default;
TcpTransport& TcpTransport::operator=(TcpTransport&&) noexcept = default;
TcpTransport::~TcpTransport() = default;

Expected<TcpTransport> TcpTransport::connect(const std::string& endpoint,
                                             std::chrono::milliseconds timeout) {
  const auto colon = endpoint.rfind(':');
  if (colon == std::string::npos || colon + 1 == endpoint.size()) {
    return fail(ErrorCode::usage, "expected HOST:PORT, got '" + endpoint + "'", {{}, 0, "--tcp"});
  }
  auto s = std::make_unique<Socket>();
  asio::ip::tcp::resolver resolver(s->io);
  boost::system::error_code ec;
  const auto addresses =
      resolver.resolve(endpoint.substr(0, colon), endpoint.substr(colon + 1), ec);
  if (ec) {
    return fail(ErrorCode::machine_fault, "cannot resolve: " + ec.message(), {endpoint, 0, {}});
  }
  boost::system::error_code connect_ec = asio::error::timed_out;
  asio::async_connect(s->socket, addresses,
                      [&](const boost::system::error_code& e, const auto&) { connect_ec = e; });
  s->io.run_for(timeout);
  if (connect_ec) {
    return fail(ErrorCode::machine_fault,
                connect_ec == asio::error::timed_out
                    ? "no connection within " + std::to_string(timeout.count()) + " ms"
                    : "cannot connect: " + connect_ec.message(),
                {endpoint, 0, {}});
  }
  s->socket.set_option(asio::ip::tcp::no_delay(true));
  s->socket.non_blocking(true);
  return TcpTransport(std::move(s), endpoint);
}

int TcpTransport::poll_fd() const {
  return socket_->socket.native_handle();
}

Expected<bool> TcpTransport::wait(short events, std::chrono::milliseconds timeout) const {
  pollfd p{poll_fd(), events, 0};
  const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (ready < 0) {
    return errno == EINTR ? Expected<bool>(false)
                          : fail(ErrorCode::machine_fault, "poll failed", {name_, 0, {}});
  }
  return ready > 0;
}

Expected<std::size_t> TcpTransport::read(std::span<char> buffer,
                                         std::chrono::milliseconds timeout) {
  SUBFEED_TRY_ASSIGN(const bool ready, wait(POLLIN, timeout));
  if (!ready) {
    return 0;
  }
  boost::system::error_code ec;
  const std::size_t n = socket_->socket.read_some(asio::buffer(buffer.data(), buffer.size()), ec);
  if (ec == asio::error::would_block) {
    return 0;
  }
  if (ec) {
    return fail(ErrorCode::machine_fault,
                ec == asio::error::eof ? "connection closed by the controller"
                                       : "connection lost: " + ec.message(),
                {name_, 0, {}});
  }
  return n;
}

Expected<std::size_t> TcpTransport::write(std::span<const char> bytes,
                                          std::chrono::milliseconds timeout) {
  SUBFEED_TRY_ASSIGN(const bool ready, wait(POLLOUT, timeout));
  if (!ready) {
    return 0;
  }
  boost::system::error_code ec;
  const std::size_t n = socket_->socket.write_some(asio::buffer(bytes.data(), bytes.size()), ec);
  if (ec == asio::error::would_block) {
    return 0;
  }
  if (ec) {
    return fail(ErrorCode::machine_fault, "connection lost: " + ec.message(), {name_, 0, {}});
  }
  return n;
}

} // namespace subfeed::drivers
