// StationLink: the station's side of the display link (protocol 6,
// docs/link-protocol.md), driven from the station's loop after Station::poll(). A
// thin coordinator of four parts, one job each:
//   LinkAdmission  who the display is: handshakes on the display's and the
//                  newcomer's channel, the pre-shared-key challenge-response,
//                  displacement and refusals (station_link_admission.hpp);
//   MeshMirror     the committed mesh: a full mesh when the display holds another
//                  version, then one change set per commit (station_link_mirror.hpp);
//   LiveStream     hands, live stroke, object pose and status (station_link_live.hpp);
//   FrameQueues    the urgent and bulk queues and their flush (station_link_queues.hpp);
//   StationSpectators  read-only displays beside the main one, each on its own
//                  bounded queues, served after it (station_link_spectators.hpp).
// The admitted display's commands (its undo / redo / method keys) go into the
// session's command path here, in core (SculptSession::submit / Station::submit,
// the hands' buttons' path): they run at the next step and report as its events.
// Never slows the station: frames go into fixed buffers flushed as the port
// accepts bytes; with no display the station keeps working. No heap: shadow mesh
// and bulk buffer are caller storage. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_link_admission.hpp"
#include "twister/station/station_link_live.hpp"
#include "twister/station/station_link_mirror.hpp"
#include "twister/station/station_link_queues.hpp"
#include "twister/station/station_link_spectators.hpp"
#include "twister/station/station_link_visitor.hpp"
#include "twister/station/station_status.hpp"

namespace twister::station {

class Station;

struct StationLinkStorage {
  // Shadow of the mesh the bridge was sent; each at least the mesh capacity.
  std::span<float> x;
  std::span<float> y;
  std::span<float> z;
  std::span<std::uint32_t> triangle_indices;  // 3 * triangle capacity
  std::span<std::byte> out;                   // bulk bytes, >= 4 * link::kMaxFrameBytes
};

struct StationLinkConfig {
  ports::TimestampUs live_interval_us = 8'000;  // at most one hands update per interval
  ports::TimestampUs status_interval_us = 1'000'000;
  ports::TimestampUs stroke_repeat_us = 1'000'000;      // stroke message repeated while open
  ports::TimestampUs handshake_timeout_us = 2'000'000;  // a newcomer's hello and auth
  // The hands' working volume and up axis, sent once after each admission.
  link::Workspace workspace{};
};

// The parts' counters in one place (for logs and tests).
struct StationLinkCounters {
  std::uint64_t connects = 0;     // displays admitted
  std::uint64_t disconnects = 0;  // display channel lost
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
  std::uint64_t live_sent = 0;     // hands updates
  std::uint64_t live_dropped = 0;  // hands updates that found no room
  std::uint64_t resend_requests = 0;
  std::uint64_t newcomers = 0;         // peers that arrived on the newcomer channel
  std::uint64_t displaced = 0;         // displays told "displaced" by an admitted newcomer
  LinkRefusals refused{};              // by why
  std::uint64_t commands = 0;          // display commands the session queued
  std::uint64_t commands_refused = 0;  // from a display not admitted, or queue full
  std::uint32_t spectators_now = 0;    // read-only displays connected
  SpectatorCounters spectators{};      // all spectators so far (issue 25)
};

// The session command of a display's command (link message `command`).
session::SessionCommand session_command(const link::Command& command);

class StationLink final : private AdmissionListener {
 public:
  StationLink(ports::LinkPort& port, StationLinkStorage storage, const StationLinkConfig& config,
              const StationLinkOptions& options = {});

  // Takes the session's current mesh as version 1. resource_exhausted: the shadow
  // or buffer storage is smaller than the mesh's capacity / link::kMaxFrameBytes * 4.
  Status start(const session::SculptSession& session);

  // One step (never blocks): handshakes, the display's requests, a new commit, a
  // full send in progress, hands / stroke / object / status updates, flush; then the
  // display's commands into the session's command path (run by its next step).
  void poll(Station& station, ports::TimestampUs now_us);
  void poll(session::SculptSession& session, const StationStatus& status,
            ports::TimestampUs now_us);
  void poll(session::SculptSession& session, ports::TimestampUs now_us) {
    poll(session, StationStatus{}, now_us);
  }
  // Tells the display the station stops (bye: shutdown), best effort.
  void say_goodbye();

  bool connected() const { return admission_.connected(); }
  bool admitted() const { return admission_.admitted(); }
  std::uint32_t mesh_version() const { return mirror_.version(); }
  // Bytes waiting for the port (0 = everything handed to the peer).
  std::size_t pending_bytes() const { return queues_.pending_bytes(); }
  bool idle() const { return pending_bytes() == 0 && mirror_.idle(); }
  // Spectators (issue 25): how many slots, and one slot as of the last poll.
  std::size_t spectator_slots() const { return spectators_.slots(); }
  SpectatorView spectator(std::size_t slot) const { return spectators_.view(slot); }
  std::size_t spectator_pending_bytes() const { return spectators_.pending_bytes(); }
  // Every spectator holds everything queued for it (its mesh sent, its queues empty).
  bool spectators_idle() const { return spectators_.idle(); }
  // A display was admitted and everything it needs has been handed to the port.
  bool peer_synced() const { return admitted() && idle(); }
  // As of the end of the last poll().
  const StationLinkCounters& counters() const { return counters_; }
  std::uint64_t send_errors() const {
    return queues_.send_errors() + admission_.counters().send_errors;
  }
  link::DecoderCounters decoder_counters() const { return admission_.decoder_counters(); }
  // The version byte of the last peer refused for speaking another protocol (0: none).
  std::uint8_t refused_version() const { return admission_.refused_version(); }

 private:
  static constexpr std::size_t kMaxCommands = 8;

  // AdmissionListener.
  void on_admitted(const MeshIdentity& holds) override;
  void on_display_lost() override;
  void on_resend_request() override;
  void on_command(const link::Command& command) override;
  MeshIdentity offered() override { return mirror_.offered(); }
  bool spectator_room() override { return spectators_.has_room(); }
  bool on_spectator(const MeshIdentity& holds) override;
  void on_spectator_command() override { spectators_.refuse_command(queues_); }

  void step(const session::SculptSession& session, const StationStatus& status,
            ports::TimestampUs now_us);
  template <class Submit>
  void route_commands(Submit submit);
  void refresh_counters();

  FrameQueues queues_;
  LinkAdmission admission_;
  MeshMirror mirror_;
  LiveStream live_;
  StationSpectators spectators_;
  bool started_ = false;
  ports::TimestampUs now_us_ = 0;  // of the poll in progress (a spectator's admission)
  std::uint32_t last_sequence_ = 0;
  // The admitted display's commands since the last poll, oldest first.
  InlineVector<link::Command, kMaxCommands> commands_;
  std::uint64_t commands_routed_ = 0;
  std::uint64_t commands_refused_ = 0;  // queue full here or in the session
  StationLinkCounters counters_{};
  VisitorFeed visitor_{};  // the main display's visitor state and notices
};

}  // namespace twister::station
