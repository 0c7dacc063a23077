#include "twister/hal/socket_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <grp.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

namespace twister::hal {
namespace {

struct Address {
  sockaddr_storage storage{};
  socklen_t length = 0;
  bool ok = false;
  bool loopback = false;
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
    a.loopback = (ntohl(in->sin_addr.s_addr) >> 24) == 127;
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
    const int one = 1;  // hands updates are small and late ones are worthless
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }
}

std::string errno_text(int err) { return std::string(std::strerror(err)); }

Expected<gid_t> group_id(const std::string& name) {
  group g{};
  group* found = nullptr;
  std::vector<char> buf(16384);
  if (getgrnam_r(name.c_str(), &g, buf.data(), buf.size(), &found) != 0 || found == nullptr) {
    return make_error(StatusCode::invalid_argument, "no group named \"" + name + "\"");
  }
  return found->gr_gid;
}

}  // namespace

SocketLink::SocketLink(SocketLinkConfig config) : config_(std::move(config)) {
  const Address a = parse(config_.address);
  address_ = a.storage;
  address_length_ = a.length;
  address_ok_ = a.ok;
  loopback_ = a.loopback;
}

SocketLink::~SocketLink() { close(); }

void SocketLink::close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

void SocketLink::close() {
  close_fd(peer_fd_);
  close_fd(newcomer_fd_);
  for (int& fd : spectator_fds_) close_fd(fd);
  while (!pending_.empty()) drop_pending(pending_.size() - 1);
  close_fd(listen_fd_);
  if (made_file_) {
    // Only the socket file this server made: a file put there since is left alone.
    const char* path = reinterpret_cast<const sockaddr_un*>(&address_)->sun_path;
    struct stat st {};
    if (::lstat(path, &st) == 0 && S_ISSOCK(st.st_mode) && st.st_dev == made_dev_ &&
        st.st_ino == made_ino_) {
      ::unlink(path);
    }
    made_file_ = false;
  }
}

Expected<void> SocketLink::prepare_unix_path() {
  const char* path = reinterpret_cast<const sockaddr_un*>(&address_)->sun_path;
  struct stat st {};
  if (::lstat(path, &st) != 0) {
    if (errno == ENOENT) return {};
    return make_error(StatusCode::io_error,
                      std::string("cannot inspect ") + path + ": " + errno_text(errno));
  }
  if (!S_ISSOCK(st.st_mode)) {
    return make_error(StatusCode::failed_precondition,
                      std::string(path) + " exists and is not a socket; left untouched");
  }
  // A socket file: stale (nobody listens: connect is refused) or a live program's.
  // Non-blocking: a listener whose backlog is full answers EAGAIN at once instead
  // of holding start-up (and the journal's lock) until it accepts.
  const int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (probe < 0) return make_error(StatusCode::io_error, "socket: " + errno_text(errno));
  const int rc = ::connect(probe, reinterpret_cast<const sockaddr*>(&address_), address_length_);
  const int err = errno;
  ::close(probe);
  if (rc == 0 || err == EAGAIN || err == EINPROGRESS) {
    return make_error(StatusCode::failed_precondition,
                      std::string(path) +
                          ": another process (a running station?) listens on it; refusing to "
                          "take it over");
  }
  if (err != ECONNREFUSED) {
    return make_error(StatusCode::io_error, std::string("cannot tell whether ") + path +
                                                " is in use: " + errno_text(err));
  }
  if (::unlink(path) != 0) {
    return make_error(StatusCode::io_error, std::string("cannot replace the stale socket ") + path +
                                                ": " + errno_text(errno));
  }
  return {};
}

Expected<void> SocketLink::open() {
  if (!address_ok_) {
    return make_error(StatusCode::invalid_argument, "bad link address \"" + config_.address +
                                                        "\" (unix:PATH | tcp:A.B.C.D:PORT)");
  }
  if (!config_.server) return {};
  const int family = address_.ss_family;
  if (family == AF_INET && !loopback_ && !config_.allow_network) {
    return make_error(StatusCode::invalid_argument,
                      config_.address +
                          " listens beyond loopback: set [link] listen = \"network\" and a "
                          "psk_file, or use 127.0.0.1");
  }
  if (family == AF_UNIX) {
    if (auto ready = prepare_unix_path(); !ready) return ready;
  }
  return listen_now();
}

Expected<void> SocketLink::listen_now() {
  const int family = address_.ss_family;
  listen_fd_ = ::socket(family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) {
    last_errno_ = errno;
    return make_error(StatusCode::io_error, "socket: " + errno_text(errno));
  }
  const int one = 1;
  if (family == AF_INET) setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&address_), address_length_) != 0) {
    last_errno_ = errno;
    close_fd(listen_fd_);
    return make_error(StatusCode::io_error, config_.address + ": bind: " + errno_text(last_errno_));
  }
  if (family == AF_UNIX) {
    // Mode and group before listen(): until then nobody can connect, whatever
    // mode the umask gave the new file.
    const char* path = reinterpret_cast<const sockaddr_un*>(&address_)->sun_path;
    struct stat st {};
    ::lstat(path, &st);
    made_file_ = true;
    made_dev_ = st.st_dev;
    made_ino_ = st.st_ino;
    if (::chmod(path, static_cast<mode_t>(config_.socket_mode)) != 0) {
      last_errno_ = errno;
      close();
      return make_error(StatusCode::io_error,
                        std::string("chmod ") + path + ": " + errno_text(last_errno_));
    }
    if (!config_.socket_group.empty()) {
      const Expected<gid_t> gid = group_id(config_.socket_group);
      if (!gid || ::chown(path, static_cast<uid_t>(-1), *gid) != 0) {
        last_errno_ = errno;
        close();
        return make_error(gid ? StatusCode::io_error : StatusCode::invalid_argument,
                          std::string("group of ") + path + ": " +
                              (gid ? errno_text(last_errno_) : gid.error().message));
      }
    }
  }
  if (::listen(listen_fd_, 64) != 0) {  // a burst of connects is accepted, not dropped
    last_errno_ = errno;
    close();
    return make_error(StatusCode::io_error,
                      config_.address + ": listen: " + errno_text(last_errno_));
  }
  return {};
}

std::size_t SocketLink::do_poll_fds(std::span<pollfd> out) const {
  std::size_t n = 0;
  for (const int fd : {peer_fd_, newcomer_fd_, listen_fd_}) {
    if (fd >= 0 && n < out.size()) out[n++] = {fd, POLLIN, 0};
  }
  for (const int fd : spectator_fds_) {
    if (fd >= 0 && n < out.size()) out[n++] = {fd, POLLIN, 0};
  }
  for (const Pending& p : pending_) {
    if (n < out.size()) out[n++] = {p.fd, POLLIN, 0};
  }
  return n;
}

Status SocketLink::do_reopen() {
  close();
  next_attempt_ms_ = 0;
  const Expected<void> opened = open();
  return opened ? ok_status() : opened.error().status;
}

void SocketLink::accept_newcomers() {
  if (listen_fd_ < 0) return;
  const std::int64_t now = now_ms();
  expire_pending(now);
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) break;
    // The station sends the hands updates: its side needs TCP_NODELAY most.
    tune(fd, address_.ss_family);
    ++accepted_;
    add_pending(fd, now);
  }
  promote_newcomer();
}

std::uint64_t SocketLink::do_newcomer_id() {
  accept_newcomers();
  return newcomer_id_;
}

void SocketLink::do_admit_newcomer() {
  if (newcomer_fd_ < 0) return;
  close_fd(peer_fd_);
  peer_fd_ = newcomer_fd_;
  newcomer_fd_ = -1;
  ++connects_;
}

void SocketLink::do_refuse_newcomer() { close_fd(newcomer_fd_); }

std::size_t SocketLink::do_spectator_capacity() const {
  return config_.server ? kSpectatorSlots : 0;
}

Status SocketLink::do_admit_spectator(std::size_t slot) {
  if (slot >= kSpectatorSlots) return StatusCode::out_of_range;
  if (newcomer_fd_ < 0) return StatusCode::unavailable;
  close_fd(spectator_fds_[slot]);  // free by contract; never leak one
  spectator_fds_[slot] = newcomer_fd_;
  newcomer_fd_ = -1;
  return ok_status();
}

Result<std::size_t> SocketLink::do_send_spectator(std::size_t slot,
                                                  std::span<const std::byte> src) {
  if (slot >= kSpectatorSlots) return StatusCode::unavailable;
  return send_on(spectator_fds_[slot], src);
}

Result<std::size_t> SocketLink::do_receive_spectator(std::size_t slot, std::span<std::byte> dest) {
  if (slot >= kSpectatorSlots) return StatusCode::unavailable;
  return receive_on(spectator_fds_[slot], dest);
}

void SocketLink::do_close_spectator(std::size_t slot) {
  if (slot < kSpectatorSlots) close_fd(spectator_fds_[slot]);
}

bool SocketLink::connect_within(int fd, int timeout_ms) {
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address_), address_length_) == 0) {
    return true;
  }
  if (errno != EINPROGRESS) {
    last_errno_ = errno;
    return false;
  }
  pollfd p{fd, POLLOUT, 0};
  int n = 0;
  do {
    n = ::poll(&p, 1, timeout_ms);
  } while (n < 0 && errno == EINTR);
  int err = n == 0 ? ETIMEDOUT : 0;
  socklen_t len = sizeof err;
  if (n > 0) ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len);
  if (n < 0) err = errno;
  last_errno_ = err;
  return err == 0;
}

bool SocketLink::ensure_client() {
  if (peer_fd_ >= 0) return true;
  const std::int64_t now = now_ms();
  if (now < next_attempt_ms_) return false;
  next_attempt_ms_ = now + config_.reconnect_interval_ms;
  if (!address_ok_) return false;
  const int fd = ::socket(address_.ss_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    last_errno_ = errno;
    return false;
  }
  // Non-blocking, with a deadline: a Unix listener with a full backlog answers
  // EAGAIN (try again later); a TCP connect gets kConnectTimeoutMs to complete.
  if (!connect_within(fd, kConnectTimeoutMs)) {
    ::close(fd);
    return false;
  }
  tune(fd, address_.ss_family);
  peer_fd_ = fd;
  ++connects_;
  return true;
}

Result<std::size_t> SocketLink::send_on(int& fd, std::span<const std::byte> src) {
  if (fd < 0) return StatusCode::unavailable;
  if (src.empty()) return std::size_t{0};
  const ssize_t n = ::send(fd, src.data(), src.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  if (n >= 0) return static_cast<std::size_t>(n);
  if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return std::size_t{0};
  last_errno_ = errno;
  close_fd(fd);
  return StatusCode::unavailable;
}

Result<std::size_t> SocketLink::receive_on(int& fd, std::span<std::byte> dest) {
  if (fd < 0) return StatusCode::unavailable;
  if (dest.empty()) return std::size_t{0};
  const ssize_t n = ::recv(fd, dest.data(), dest.size(), MSG_DONTWAIT);
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return std::size_t{0};
  last_errno_ = n == 0 ? 0 : errno;  // 0: orderly close by the peer
  close_fd(fd);
  return StatusCode::unavailable;
}

Result<std::size_t> SocketLink::do_send(std::span<const std::byte> src) {
  if (!config_.server && !ensure_client()) return StatusCode::unavailable;
  return send_on(peer_fd_, src);
}

Result<std::size_t> SocketLink::do_receive(std::span<std::byte> dest) {
  if (!config_.server && !ensure_client()) return StatusCode::unavailable;
  return receive_on(peer_fd_, dest);
}

// Newcomers are accepted only in newcomer_id(), so the station sees every change of
// newcomer (and starts its decoder afresh) before it reads from the new one.
Result<std::size_t> SocketLink::do_send_newcomer(std::span<const std::byte> src) {
  return send_on(newcomer_fd_, src);
}

Result<std::size_t> SocketLink::do_receive_newcomer(std::span<std::byte> dest) {
  return receive_on(newcomer_fd_, dest);
}

}  // namespace twister::hal
