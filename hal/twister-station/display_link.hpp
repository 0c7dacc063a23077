// DisplayLink: twister-station's optional link to twister-bridge (--link ADDRESS):
// a listening hal::SocketLink plus core's StationLink with its storage sized once from
// the mesh capacity. The station never waits for it except where asked:
// wait_for_peer() before the run (demo/tests in virtual time) and drain() at exit;
// both wait on the socket's readiness. poll() and poll_fds() run in the station's
// loop and never allocate.
#pragma once

#include <poll.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/hal/socket_link.hpp"
#include "twister/station/station_link.hpp"

namespace twister::station_app {

class DisplayLink {
 public:
  // Binds `address` and takes the session's mesh as version 1. Errors: the
  // socket's status (invalid_argument: bad address; io_error: bind failed) or the
  // StationLink's (resource_exhausted), with a message naming the link.
  hal::Expected<void> open(const std::string& address, const input::SculptSession& session);
  bool is_open() const { return link_ != nullptr; }
  void poll(const input::SculptSession& session, ports::TimestampUs now_us);
  // The link's descriptors for the loop's poll set (none without --link).
  std::size_t poll_fds(std::span<pollfd> out) const { return socket_ ? socket_->poll_fds(out) : 0; }
  // Real-time wait: true when a peer holds our mesh within `seconds`.
  bool wait_for_peer(const input::SculptSession& session, double seconds);
  // Hands everything queued to the peer (up to `seconds`).
  void drain(const input::SculptSession& session, ports::TimestampUs now_us, double seconds);
  const station::StationLinkCounters* counters() const {
    return link_ ? &link_->counters() : nullptr;
  }

 private:
  // Waits up to timeout_ms for the socket: input, a peer, or room for pending bytes.
  void wait_ready(int timeout_ms) const;

  std::unique_ptr<hal::SocketLink> socket_;
  std::vector<float> x_, y_, z_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::byte> out_;
  std::unique_ptr<station::StationLink> link_;
};

}  // namespace twister::station_app
