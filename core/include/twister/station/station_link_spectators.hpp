// StationSpectators: the read-only displays of issue 25 (a projector, a monitor
// facing the queue) beside the one display that may send commands. Each spectator
// was authenticated like the main display (LinkAdmission) and sits in one of
// max_spectators slots of a transport that offers them (ports::LinkSpectators).
// Per slot: its own queues (the fixed urgent queue and a bounded bulk queue of
// caller storage), its own LiveStream (hands, stroke, object, status: a spectator
// admitted mid-stroke gets the stroke's begin at once), its visitor state and
// notices (VisitorFeed) and where its mesh stands
// (MeshSendState): first the full committed mesh from MeshMirror's shadow, then each
// commit's change set copied from MeshMirror::staged() (one encoding for everyone).
// A slow spectator never slows the station or the main display: StationLink serves
// the main display first, a hands update that finds no room in a spectator's queue
// is dropped and counted, a commit that finds no room becomes a full send (counted:
// commits_resent), and a spectator that takes no byte for stall_timeout_us is
// dropped (closed, counted). A spectator's commands are refused with a notice
// (command_refused_spectator). No heap. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/link/link_codec.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/link_spectators.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_link_live.hpp"
#include "twister/station/station_link_mirror.hpp"
#include "twister/station/station_link_queues.hpp"
#include "twister/station/station_link_visitor.hpp"
#include "twister/station/station_status.hpp"

namespace twister::station {

class Station;

// Slots a station can have ([link] max_spectators is at most this).
inline constexpr std::size_t kMaxSpectators = 8;

struct SpectatorCounters {
  std::uint64_t admitted = 0;
  std::uint64_t left = 0;              // said bye or hung up
  std::uint64_t dropped = 0;           // took no byte for stall_timeout_us: closed
  std::uint64_t commands_refused = 0;  // answered with notice command_refused_spectator
  std::uint64_t live_sent = 0;         // hands updates
  std::uint64_t live_dropped = 0;      // hands updates that found no room
  std::uint64_t commits_sent = 0;      // change sets copied into its queue
  std::uint64_t commits_resent = 0;    // commits that found no room: a full send instead
  std::uint64_t full_sends = 0;
  std::uint64_t resend_requests = 0;
  SpectatorCounters& operator+=(const SpectatorCounters& o);
};

// One slot as of the last poll (counters of its current occupant).
struct SpectatorView {
  bool open = false;
  SpectatorCounters counters{};
  std::size_t pending_bytes = 0;
};

// One slot's channel as a LinkPort, for its FrameQueues.
class SpectatorChannel final : public ports::LinkPort {
 public:
  void bind(ports::LinkSpectators* port, std::size_t slot) {
    port_ = port;
    slot_ = slot;
  }

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override;
  Result<std::size_t> do_receive(std::span<std::byte> dest) override;
  ports::LinkSpectators* port_ = nullptr;
  std::size_t slot_ = 0;
};

// One spectator slot: channel, queues, live stream, mesh state, decoder.
class Spectator {
 public:
  explicit Spectator(const LiveStreamConfig& live) : queues_(channel_, {}), live_(queues_, live) {}
  Spectator(const Spectator&) = delete;
  Spectator& operator=(const Spectator&) = delete;

  bool open() const { return open_; }
  SpectatorView view() const;

 private:
  friend class StationSpectators;
  SpectatorChannel channel_;
  FrameQueues queues_;
  LiveStream live_;
  VisitorFeed visitor_{};
  MeshSendState mesh_{};
  link::LinkDecoder decoder_;
  bool open_ = false;
  bool catching_up_ = false;            // its mesh is on its way (a full send)
  ports::TimestampUs progress_us_ = 0;  // when it last took bytes (or had none waiting)
  LiveCounters live_base_{};            // live_'s counters at admission
  SpectatorCounters counters_{};        // this occupant's (live_* from live_)
};

struct SpectatorConfig {
  std::size_t max_spectators = 0;  // slots used (at most kMaxSpectators and the transport's)
  ports::TimestampUs stall_timeout_us = 5'000'000;  // no byte taken this long: dropped
};

class StationSpectators {
 public:
  StationSpectators(ports::LinkSpectators* port, const SpectatorConfig& config,
                    const LiveStreamConfig& live, std::span<std::byte> queues);

  // Splits the queue storage between the slots. resource_exhausted: less than
  // 4 frames (link::kMaxFrameBytes) per slot, or slots without a transport.
  Status start();
  std::size_t slots() const { return slots_used_; }
  bool has_room() const;
  // The waiting newcomer (authenticated) becomes a spectator holding `holds`; false
  // when no slot is free or the transport refused (nothing changed).
  bool admit(MeshMirror& mirror, const MeshIdentity& holds, ports::TimestampUs now_us);
  // A spectator could take the next commit as a change set.
  bool any_current() const;
  // After MeshMirror::track(): each current spectator gets `staged` when its queue
  // has room for all of it, else a full send.
  void on_commit(std::span<const std::byte> staged);
  // Reads every spectator, queues what is due, flushes, drops the stalled.
  void poll(const session::SculptSession& session, const StationStatus& status, MeshMirror& mirror,
            ports::TimestampUs now_us);
  // Each open spectator's visitor state and notices (VisitorFeed), as the main display's.
  void send_visitor(const Station& station, ports::TimestampUs now_us);
  // A read-only display on the main channel (serial) sent a command: refused on `out`.
  void refuse_command(FrameQueues& out);
  // Tells every spectator the station stops (bye: shutdown), best effort.
  void say_goodbye();

  std::size_t count() const;
  // All spectators so far, the present ones included.
  SpectatorCounters totals() const;
  SpectatorView view(std::size_t slot) const;
  std::size_t pending_bytes() const;
  // No spectator has bytes waiting or a full send due or in progress.
  bool idle() const;

 private:
  void read(Spectator& s);
  void on_message(Spectator& s, const link::LinkMessage& m);
  void close(Spectator& s, std::uint64_t SpectatorCounters::*why);

  std::array<Spectator, kMaxSpectators> slots_;
  ports::LinkSpectators* port_;
  SpectatorConfig config_;
  std::span<std::byte> queue_bytes_;
  std::size_t slots_used_ = 0;
  SpectatorCounters closed_{};  // spectators that left, and refusals on the main channel
};

}  // namespace twister::station
