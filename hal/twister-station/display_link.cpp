#include "display_link.hpp"

#include <algorithm>
#include <array>
#include <chrono>

namespace twister::station_app {
namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds left until `until`, at most 50 (so the link's own timers run).
int ms_left(Clock::time_point until) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
  return static_cast<int>(std::clamp<std::int64_t>(left.count(), 0, 50));
}

}  // namespace

hal::Expected<void> DisplayLink::open(const std::string& address,
                                      const input::SculptSession& session) {
  socket_ = std::make_unique<hal::SocketLink>(hal::SocketLinkConfig{address, true, 200});
  if (const Status s = socket_->open(); !s.ok()) {
    return hal::Error{s, "link " + address + ": " + s.name() + " (errno " +
                             std::to_string(socket_->last_errno()) + ")"};
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
  if (const Status s = link_->start(session); !s.ok()) {
    return hal::Error{s, std::string("link: ") + s.name()};
  }
  return {};
}

void DisplayLink::poll(const input::SculptSession& session, ports::TimestampUs now_us) {
  if (link_) link_->poll(session, now_us);
}

void DisplayLink::wait_ready(int timeout_ms) const {
  std::array<pollfd, hal::PollSource::kMaxFds> fds{};
  const std::size_t n = socket_->poll_fds(fds);
  // The peer's descriptor comes first; wait for room only while bytes are queued.
  if (n > 0 && socket_->connected() && link_->pending_bytes() > 0) fds[0].events |= POLLOUT;
  ::poll(fds.data(), n, timeout_ms);
}

bool DisplayLink::wait_for_peer(const input::SculptSession& session, double seconds) {
  if (!link_) return false;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
  while (Clock::now() < until) {
    link_->poll(session, 0);
    if (link_->peer_synced()) return true;
    wait_ready(ms_left(until));
  }
  return false;
}

void DisplayLink::drain(const input::SculptSession& session, ports::TimestampUs now_us,
                        double seconds) {
  if (!link_) return;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
  while (link_->connected() && !link_->idle() && Clock::now() < until) {
    link_->poll(session, now_us);
    if (!link_->idle()) wait_ready(ms_left(until));
  }
}

}  // namespace twister::station_app
