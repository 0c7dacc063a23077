#include "display_link.hpp"

#include <poll.h>

#include <chrono>

namespace twister::station_app {

std::string DisplayLink::open(const std::string& address, const input::SculptSession& session) {
  socket_ = std::make_unique<hal::SocketLink>(hal::SocketLinkConfig{address, true, 200});
  if (const Status s = socket_->open(); !s.ok()) {
    return "link " + address + ": " + s.name() + " (errno " +
           std::to_string(socket_->last_errno()) + ")";
  }
  const std::size_t n = session.mesh().vertex_capacity();
  x_.resize(n);
  y_.resize(n);
  z_.resize(n);
  indices_.resize(3 * session.mesh().triangle_capacity());
  // Room for a few hundred frames: a whole commit of a large stroke fits at once.
  out_.resize(512 * link::kMaxFrameBytes);
  link_ = std::make_unique<station::StationLink>(
      *socket_, station::StationLinkStorage{x_, y_, z_, indices_, out_},
      station::StationLinkConfig{});
  if (const Status s = link_->start(session); !s.ok()) return std::string("link: ") + s.name();
  return {};
}

void DisplayLink::poll(const input::SculptSession& session, ports::TimestampUs now_us) {
  if (link_) link_->poll(session, now_us);
}

bool DisplayLink::wait_for_peer(const input::SculptSession& session, double seconds) {
  if (!link_) return false;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    link_->poll(session, 0);
    if (link_->peer_synced()) return true;
    ::poll(nullptr, 0, 5);
  }
  return false;
}

void DisplayLink::drain(const input::SculptSession& session, ports::TimestampUs now_us,
                        double seconds) {
  if (!link_) return;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (link_->connected() && !link_->idle() && std::chrono::steady_clock::now() < until) {
    link_->poll(session, now_us);
    ::poll(nullptr, 0, 2);
  }
}

}  // namespace twister::station_app
