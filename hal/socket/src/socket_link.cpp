#include "twister/hal/socket_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace twister::hal {
namespace {

struct Address {
  sockaddr_storage storage{};
  socklen_t length = 0;
  int family = AF_UNIX;
  bool ok = false;
};

Address parse(const std::string& text) {
  Address a;
  if (text.rfind("unix:", 0) == 0) {
    const std::string path = text.substr(5);
    auto* un = reinterpret_cast<sockaddr_un*>(&a.storage);
    if (path.empty() || path.size() >= sizeof un->sun_path) return a;
    un->sun_family = AF_UNIX;
    std::memcpy(un->sun_path, path.c_str(), path.size() + 1);
    a.length = static_cast<socklen_t>(sizeof(sockaddr_un));
    a.family = AF_UNIX;
    a.ok = true;
  } else if (text.rfind("tcp:", 0) == 0) {
    const std::string rest = text.substr(4);
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) return a;
    auto* in = reinterpret_cast<sockaddr_in*>(&a.storage);
    in->sin_family = AF_INET;
    if (inet_pton(AF_INET, rest.substr(0, colon).c_str(), &in->sin_addr) != 1) return a;
    char* end = nullptr;
    const long port = std::strtol(rest.c_str() + colon + 1, &end, 10);
    if (end == nullptr || *end != '\0' || port < 1 || port > 65535) return a;
    in->sin_port = htons(static_cast<std::uint16_t>(port));
    a.length = static_cast<socklen_t>(sizeof(sockaddr_in));
    a.family = AF_INET;
    a.ok = true;
  }
  return a;
}

std::int64_t now_ms() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000 + ts.tv_nsec / 1'000'000;
}

void tune(int fd, int family) {
  if (family == AF_INET) {
    const int one = 1;  // live frames are small and late ones are worthless
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }
}

}  // namespace

SocketLink::SocketLink(SocketLinkConfig config) : config_(std::move(config)) {
  const Address a = parse(config_.address);
  address_ = a.storage;
  address_length_ = a.length;
  address_ok_ = a.ok;
}

SocketLink::~SocketLink() {
  drop_peer();
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

Status SocketLink::open() {
  if (!address_ok_) return StatusCode::invalid_argument;
  if (!config_.server) return ok_status();
  const int family = address_.ss_family;
  if (family == AF_UNIX) ::unlink(reinterpret_cast<const sockaddr_un*>(&address_)->sun_path);
  listen_fd_ = ::socket(family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) {
    last_errno_ = errno;
    return StatusCode::io_error;
  }
  const int one = 1;
  setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&address_), address_length_) != 0 ||
      ::listen(listen_fd_, 2) != 0) {
    last_errno_ = errno;
    ::close(listen_fd_);
    listen_fd_ = -1;
    return StatusCode::io_error;
  }
  return ok_status();
}

std::size_t SocketLink::do_poll_fds(std::span<pollfd> out) const {
  std::size_t n = 0;
  for (const int fd : {peer_fd_, listen_fd_}) {
    if (fd >= 0 && n < out.size()) out[n++] = {fd, POLLIN, 0};
  }
  return n;
}

Status SocketLink::do_reopen() {
  drop_peer();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
  next_attempt_ms_ = 0;
  return open();
}

void SocketLink::drop_peer() {
  if (peer_fd_ >= 0) ::close(peer_fd_);
  peer_fd_ = -1;
}

bool SocketLink::ensure_peer() {
  if (config_.server) {
    if (listen_fd_ < 0) return false;
    // Accept every waiting peer; the newest wins (a restarted bridge).
    for (;;) {
      const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) break;
      // The station sends the live frames: its side needs TCP_NODELAY most.
      tune(fd, address_.ss_family);
      drop_peer();
      peer_fd_ = fd;
      ++connects_;
    }
    return peer_fd_ >= 0;
  }
  if (peer_fd_ >= 0) return true;
  const std::int64_t now = now_ms();
  if (now < next_attempt_ms_) return false;
  next_attempt_ms_ = now + config_.reconnect_interval_ms;
  if (!address_ok_) return false;
  const int fd = ::socket(address_.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    last_errno_ = errno;
    return false;
  }
  // A blocking connect is immediate on loopback/Unix sockets (refused or accepted).
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address_), address_length_) != 0) {
    last_errno_ = errno;
    ::close(fd);
    return false;
  }
  const int flags = fcntl(fd, F_GETFL);
  fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  tune(fd, address_.ss_family);
  peer_fd_ = fd;
  ++connects_;
  return true;
}

Result<std::size_t> SocketLink::do_send(std::span<const std::byte> src) {
  if (!ensure_peer()) return StatusCode::unavailable;
  if (src.empty()) return std::size_t{0};
  const ssize_t n = ::send(peer_fd_, src.data(), src.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  if (n >= 0) return static_cast<std::size_t>(n);
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return std::size_t{0};
  last_errno_ = errno;
  drop_peer();
  return StatusCode::unavailable;
}

Result<std::size_t> SocketLink::do_receive(std::span<std::byte> dest) {
  if (!ensure_peer()) return StatusCode::unavailable;
  if (dest.empty()) return std::size_t{0};
  const ssize_t n = ::recv(peer_fd_, dest.data(), dest.size(), MSG_DONTWAIT);
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return std::size_t{0};
  last_errno_ = n == 0 ? 0 : errno;  // 0: orderly close by the peer
  drop_peer();
  return StatusCode::unavailable;
}

}  // namespace twister::hal
