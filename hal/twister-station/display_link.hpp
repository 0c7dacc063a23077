// DisplayLink: twister-station's optional link to twister-bridge ([link] in
// station.toml, --link overrides the address): the transport (a listening
// hal::SocketLink on unix:/tcp:, or a hal::SerialLink on serial:), the pre-shared
// key when configured (hal::SodiumAuthenticator), and core's StationLink with its
// storage sized once from the mesh capacity. The station never waits for it except
// where asked: wait_for_peer() before the run (demo/tests in virtual time) and
// drain() at exit (which also tells the display the station stops); both wait on
// the transport's readiness. poll() and poll_fds() run in the station's loop and
// never allocate; poll() logs admissions and refusals through the logger given.
#pragma once

#include <poll.h>

#include <chrono>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "config/station_config.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/serial_link.hpp"
#include "twister/hal/socket_link.hpp"
#include "twister/hal/sodium_authenticator.hpp"
#include "twister/station/station.hpp"
#include "twister/station/station_link.hpp"

namespace twister::station_app {

class DisplayLink {
 public:
  DisplayLink();
  ~DisplayLink();
  DisplayLink(const DisplayLink&) = delete;
  DisplayLink& operator=(const DisplayLink&) = delete;

  // Opens `settings.address` and takes the session's mesh as version 1. Errors
  // name the link: the key file's (load_link_key), the transport's (SocketLink /
  // SerialLink open), or the StationLink's (resource_exhausted).
  // `workspace` goes to every admitted display (the camera frames it).
  hal::Expected<void> open(const LinkSection& settings, const session::SculptSession& session,
                           const link::Workspace& workspace, hal::Logger& log);
  bool is_open() const { return link_ != nullptr; }
  // The main display is connected and admitted now.
  bool connected() const { return link_ != nullptr && link_->admitted(); }
  // One link step; the admitted display's commands (its undo/redo/method keys) go
  // to the session's command path inside core (StationLink -> Station::submit);
  // their results come as the next step's session events, logged like the buttons'.
  void poll(station::Station& core, ports::TimestampUs now_us);
  // The link's descriptors for the loop's poll set (none without a link).
  std::size_t poll_fds(std::span<pollfd> out) const { return poll_ ? poll_->poll_fds(out) : 0; }
  // Real-time wait: true when a display holds our mesh within `seconds`.
  bool wait_for_peer(station::Station& core, double seconds);
  // Virtual time only: waits (up to `seconds` of real time) until everything queued
  // has gone to a connected display, so a display slower than the simulated clock
  // is never dropped a hands update: the same run sends the same frames.
  void settle(station::Station& core, ports::TimestampUs now_us, double seconds);
  // Hands everything queued to the display and the spectators (giving up after
  // `seconds` without progress, or a minute), then says goodbye to all.
  void drain(station::Station& core, ports::TimestampUs now_us, double seconds);
  const station::StationLinkCounters* counters() const {
    return link_ ? &link_->counters() : nullptr;
  }

 private:
  // Waits up to timeout_ms for the transport: input, a peer, or room for pending bytes.
  void wait_ready(int timeout_ms) const;
  void log_changes();
  void log_spectators(const station::StationLinkCounters& c);

  std::unique_ptr<hal::SocketLink> socket_;
  std::unique_ptr<hal::SerialLink> serial_;
  ports::LinkPort* port_ = nullptr;
  hal::PollSource* poll_ = nullptr;
  std::unique_ptr<hal::SodiumAuthenticator> auth_;
  std::vector<float> x_, y_, z_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::byte> out_;
  std::vector<std::byte> spectator_queues_, spectator_staging_;
  double stall_seconds_ = 5.0;
  std::unique_ptr<station::StationLink> link_;
  hal::Logger* log_ = nullptr;
  station::StationLinkCounters logged_{};
  std::chrono::steady_clock::time_point last_refusal_log_{};
};

}  // namespace twister::station_app
