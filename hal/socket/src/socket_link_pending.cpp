// SocketLink's pending set (server): accepted connections wait here until they have
// spoken; silent ones expire or make room, the oldest speaker becomes the newcomer
// (socket_link.hpp: admission cannot be starved).
#include <sys/socket.h>

#include <cerrno>
#include <cstddef>

#include "twister/hal/socket_link.hpp"

namespace twister::hal {
namespace {

// Peeks at an accepted connection: 1 it has spoken, 0 silent so far, -1 gone.
int peek(int fd) {
  std::byte b{};
  const ssize_t n = ::recv(fd, &b, 1, MSG_PEEK | MSG_DONTWAIT);
  if (n > 0) return 1;
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return 0;
  return -1;
}

}  // namespace

void SocketLink::add_pending(int fd, std::int64_t now_ms) {
  if (pending_.full()) {
    // Full: the oldest silent connection makes room (or the oldest of all).
    std::size_t victim = 0;
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      if (peek(pending_[i].fd) != 1) {
        victim = i;
        break;
      }
    }
    drop_pending(victim);
  }
  pending_.push_back({fd, now_ms}).ignore();  // room was made above
}

void SocketLink::drop_pending(std::size_t index) {
  close_fd(pending_[index].fd);
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
}

void SocketLink::expire_pending(std::int64_t now_ms) {
  for (std::size_t i = 0; i < pending_.size();) {
    const int state = peek(pending_[i].fd);
    const bool stale = now_ms - pending_[i].since_ms > config_.pending_timeout_ms;
    if (state < 0 || (state == 0 && stale)) {
      drop_pending(i);
    } else {
      ++i;
    }
  }
}

void SocketLink::promote_newcomer() {
  if (newcomer_fd_ >= 0) return;  // the station is still busy with the last one
  for (std::size_t i = 0; i < pending_.size();) {
    const int state = peek(pending_[i].fd);
    if (state < 0) {
      drop_pending(i);
      continue;
    }
    if (state > 0) {
      newcomer_fd_ = pending_[i].fd;
      pending_[i].fd = -1;
      drop_pending(i);
      ++newcomer_id_;
      return;
    }
    ++i;
  }
}

}  // namespace twister::hal
