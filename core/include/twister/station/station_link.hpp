// StationLink: the station's side of the display link (protocol 2,
// docs/link-protocol.md). Driven from the station's loop after Station::poll(): it
// admits a display (hello, and the pre-shared-key challenge-response when an
// authenticator is given), mirrors the session's committed mesh to it (a full mesh
// when the display holds another version, then one change set per commit: changed
// vertices, changed or new triangles, counts, version and checksum), and streams at
// the tracker rate the hands (poses, buttons), the radius and the live stroke (one
// `stroke` message per segment with the exact start frames, then compact `hands`
// updates), the object pose and the station status.
// Admission: on a port that also offers ports::LinkNewcomers (a listening socket),
// a peer that connects while a display is connected is handled on the newcomer
// channel; only when its handshake succeeds does it become the display, and the
// displaced display is told so (bye: displaced) and backs off. A stranger that
// fails the handshake, speaks another protocol version or stalls is refused and
// never disturbs the display. Every connection starts with a fresh decoder.
// Never slows the station: frames go into fixed buffers flushed as the port
// accepts bytes, the small urgent ones (hands, stroke, object, status, handshake)
// ahead of the bulk mesh frames at frame boundaries; a hands update that finds no
// room is dropped (counted); a commit is queued all or nothing, and one that does
// not fit becomes a full resend. With no display the station keeps working.
// No heap: shadow mesh and bulk buffer are caller storage. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/session/sculpt_session.hpp"
#include "twister/link/link_authenticator.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/station/station_status.hpp"

namespace twister::station {

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
};

// Optional capabilities: newcomer admission (listening transports) and the
// pre-shared-key handshake. Both must outlive the link.
struct StationLinkOptions {
  ports::LinkNewcomers* newcomers = nullptr;
  link::LinkAuthenticator* authenticator = nullptr;
};

struct StationLinkCounters {
  std::uint64_t connects = 0;     // displays admitted
  std::uint64_t disconnects = 0;  // display channel lost
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
  std::uint64_t live_sent = 0;     // hands updates
  std::uint64_t live_dropped = 0;  // hands updates that found no room
  std::uint64_t resend_requests = 0;
  std::uint64_t send_errors = 0;
  std::uint64_t newcomers = 0;             // peers that arrived on the newcomer channel
  std::uint64_t displaced = 0;             // displays told "displaced" by an admitted newcomer
  std::uint64_t refused_unauthorised = 0;  // wrong or missing tag
  std::uint64_t refused_protocol = 0;      // wrong role, order or message
  std::uint64_t refused_version = 0;       // another protocol version
  std::uint64_t refused_timeout = 0;       // handshake not finished in time
  std::uint64_t commands = 0;              // display commands accepted (take_command)
  std::uint64_t commands_refused = 0;      // from a display not admitted, or queue full
};

// The session command of a display's command (link message `command`).
session::SessionCommand session_command(const link::Command& command);

class StationLink {
 public:
  StationLink(ports::LinkPort& port, StationLinkStorage storage, const StationLinkConfig& config,
              const StationLinkOptions& options = {});

  // Takes the session's current mesh as version 1. resource_exhausted: the shadow
  // or buffer storage is smaller than the mesh's capacity / link::kMaxFrameBytes * 4.
  Status start(const session::SculptSession& session);

  // One step (never blocks): handshakes, the display's requests, a new commit, a
  // full send in progress, hands / stroke / object / status updates, flush.
  void poll(const session::SculptSession& session, const StationStatus& status,
            ports::TimestampUs now_us);
  void poll(const session::SculptSession& session, ports::TimestampUs now_us) {
    poll(session, StationStatus{}, now_us);
  }
  // The next command the admitted display sent (keys: undo, redo, method), oldest
  // first; false when none. The station routes it into the session's command path.
  // Commands from a peer that is not admitted are dropped and counted.
  bool take_command(link::Command& out);
  // Tells the display the station stops (bye: shutdown), best effort.
  void say_goodbye();

  bool connected() const { return connected_; }
  bool admitted() const { return connected_ && display_.admitted; }
  std::uint32_t mesh_version() const { return version_; }
  // Bytes waiting for the port (0 = everything handed to the peer).
  std::size_t pending_bytes() const { return out_size_ + urgent_size_; }
  bool idle() const { return pending_bytes() == 0 && !full_active_ && !full_wanted_; }
  // A display was admitted and everything it needs has been handed to the port.
  bool peer_synced() const { return admitted() && idle(); }
  const StationLinkCounters& counters() const { return counters_; }
  link::DecoderCounters decoder_counters() const { return decoder_.counters(); }
  // The version byte of the last peer refused for speaking another protocol (0: none).
  std::uint8_t refused_version() const { return refused_version_; }

 private:
  enum class FullPhase : std::uint8_t { begin, vertices, triangles, end };
  enum class Queue : std::uint8_t { none, urgent, bulk };
  // One connection's handshake (display channel or newcomer channel).
  struct Handshake {
    bool hello = false;     // the bridge's hello arrived
    bool admitted = false;  // hello (and auth) done: it is the display
    link::Nonce station_nonce{};
    link::Nonce bridge_nonce{};
    std::uint32_t have_version = 0;
    std::uint64_t have_checksum = 0;
    ports::TimestampUs since_us = 0;
  };
  static constexpr std::size_t kUrgentBytes = 8192;
  static constexpr std::size_t kMaxCommands = 8;

  // Handshakes (station_link.cpp).
  void receive(ports::TimestampUs now_us);
  void lose_display();
  void on_display_message(const link::LinkMessage& m);
  void poll_newcomer(ports::TimestampUs now_us);
  void on_newcomer_message(const link::LinkMessage& m);
  // Tells the newcomer why (bye) and closes it; `counter` (may be null) counts it.
  void refuse_newcomer(link::ByeReason reason, std::uint64_t* counter);
  void admit_newcomer();
  // Starts a handshake on `hello`; returns the station's hello to send back.
  link::LinkMessage begin_handshake(Handshake& hs, const link::Hello& hello);
  bool check_auth(const Handshake& hs, const link::Auth& auth) const;
  link::LinkMessage station_auth(const Handshake& hs) const;
  void resync(const Handshake& hs);
  // Encodes `m` and hands it straight to the newcomer (small handshake frames).
  void send_newcomer(const link::LinkMessage& m);
  void refuse_version(link::LinkDecoder& decoder);
  // Mesh (station_link_mesh.cpp).
  void track_mesh(const mesh::Mesh& mesh);
  bool queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                    std::uint32_t old_triangles);
  bool queue_changed_vertices(const mesh::Mesh& mesh, std::uint32_t old_vertices);
  bool queue_changed_triangles(const mesh::Mesh& mesh, std::uint32_t old_triangles);
  void continue_full();
  void start_full();
  // Live (station_link_live.cpp).
  void send_live(const session::SculptSession& session, const StationStatus& status,
                 ports::TimestampUs now_us);
  void send_stroke(const session::LiveWarp& live, ports::TimestampUs now_us);
  void send_hands(const session::SculptSession& session, const session::LiveWarp& live);
  void send_object(const session::SculptSession& session);
  void send_status(const session::SculptSession& session, const StationStatus& status,
                   ports::TimestampUs now_us);
  // Buffers.
  std::size_t room() const { return out_.size() - out_size_; }
  bool queue(const link::LinkMessage& m);         // bulk
  bool queue_urgent(const link::LinkMessage& m);  // urgent
  void clear_queues();
  void flush();

  ports::LinkPort& port_;
  StationLinkStorage storage_;
  StationLinkConfig config_;
  StationLinkOptions options_;
  mesh::Mesh shadow_;
  link::LinkDecoder decoder_;
  link::LinkMessage scratch_{};  // one message being built (large: kept off the stack)
  std::span<std::byte> out_;
  std::size_t out_size_ = 0;
  std::array<std::byte, kUrgentBytes> urgent_{};
  std::size_t urgent_size_ = 0;
  Queue sending_ = Queue::none;  // the queue whose frame is partly handed to the port
  bool started_ = false;
  bool connected_ = false;
  Handshake display_{};
  std::uint32_t version_ = 0;
  std::uint32_t last_sequence_ = 0;
  std::uint8_t refused_version_ = 0;
  // Newcomer channel.
  link::LinkDecoder newcomer_decoder_;
  Handshake newcomer_{};
  std::uint64_t newcomer_id_ = 0;
  bool newcomer_open_ = false;
  // Full send in progress (from the shadow).
  bool full_wanted_ = false;
  bool full_active_ = false;
  FullPhase full_phase_ = FullPhase::begin;
  std::size_t full_next_ = 0;
  // Live stroke and hands.
  bool live_was_active_ = false;
  std::uint32_t stroke_ = 0;
  std::array<math::Frame, link::kLinkHands> live_start_{};
  ports::TimestampUs last_stroke_us_ = 0;
  ports::TimestampUs last_live_us_ = 0;
  std::uint16_t hands_sequence_ = 0;
  link::Hands last_hands_{};
  bool hands_sent_ = false;
  math::Frame object_sent_{};
  bool object_sent_valid_ = false;
  ports::TimestampUs last_status_us_ = 0;
  bool status_sent_ = false;
  link::StatusReport last_status_{};
  std::array<link::Command, kMaxCommands> commands_{};
  std::size_t command_count_ = 0;
  StationLinkCounters counters_{};
};

}  // namespace twister::station
