#include "sim/tcp_listener.hpp"

#include "os_failure.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <utility>

namespace subfeed::sim {

Expected<TcpListener> TcpListener::open(const std::string& host, int port) {
  const std::string where = host + ":" + std::to_string(port);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1) {
    return fail(ErrorCode::bad_input, "not an IPv4 address", {where, 0, {}});
  }
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    return os_failure("socket", where);
  }
  TcpListener listener(fd, where);
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 1) != 0) {
    return os_failure("cannot listen", where);
  }
  socklen_t length = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length);
  listener.address_ = host + ":" + std::to_string(ntohs(addr.sin_port));
  return listener;
}

Expected<std::size_t> TcpListener::read(std::span<char> buffer, std::chrono::milliseconds timeout) {
  if (!listen_.valid()) {
    std::this_thread::sleep_for(timeout);
    return 0;
  }
  pollfd p{peer_.valid() ? peer_.get() : listen_.get(), POLLIN, 0};
  const int ready = ::poll(&p, 1, static_cast<int>(timeout.count()));
  if (ready <= 0) {
    return ready < 0 && errno != EINTR ? os_failure("poll", address_) : Expected<std::size_t>(0);
  }
  if (!peer_.valid()) {
    peer_.reset(::accept4(listen_.get(), nullptr, nullptr, SOCK_CLOEXEC));
    if (peer_.valid()) {
      const int yes = 1; // replies are tiny and latency matters
      ::setsockopt(peer_.get(), IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
    }
    return 0;
  }
  const ssize_t n = ::recv(peer_.get(), buffer.data(), buffer.size(), 0);
  if (n <= 0) {
    peer_.reset(); // the sender went away; wait for the next one
    return 0;
  }
  return static_cast<std::size_t>(n);
}

std::size_t TcpListener::unread() const {
  int n = 0;
  return peer_.valid() && ::ioctl(peer_.get(), FIONREAD, &n) == 0 && n > 0
             ? static_cast<std::size_t>(n)
             : 0;
}

Expected<void> TcpListener::write_all(std::span<const char> bytes) {
  while (peer_.valid() && !bytes.empty()) {
    const ssize_t n = ::send(peer_.get(), bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) {
        continue;
      }
      peer_.reset();
      return {};
    }
    bytes = bytes.subspan(static_cast<std::size_t>(n));
  }
  return {};
}

} // namespace subfeed::sim
