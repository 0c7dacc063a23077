// StationLink: the station's side of the display link. Driven from the station's
// loop after Station::poll(): it mirrors the session's committed mesh to the bridge
// (a full mesh on connect or on request, then one change set per commit with the
// new version and checksum) and streams the live stroke's screws while a hand
// grabs, so the display warps in its vertex shader without the CPU copy.
// The link never blocks or slows the station: frames go into a fixed outgoing
// buffer that is flushed as the port accepts bytes; a live frame that does not fit
// is dropped (the next one replaces it); a commit that does not fit turns into a
// full resend. With no peer the station keeps working; a peer that (re)connects
// says which version it holds and gets the full mesh only when it differs.
// No heap: shadow mesh and buffer are caller storage. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/input/sculpt_session.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/link_port.hpp"

namespace twister::station {

struct StationLinkStorage {
  // Shadow of the mesh the bridge was sent; each at least the mesh capacity.
  std::span<float> x;
  std::span<float> y;
  std::span<float> z;
  std::span<std::uint32_t> triangle_indices;  // 3 * triangle capacity
  std::span<std::byte> out;                   // outgoing bytes, >= 4 * link::kMaxFrameBytes
};

struct StationLinkConfig {
  ports::TimestampUs live_interval_us = 8'000;  // at most one live frame per interval
  ports::TimestampUs status_interval_us = 1'000'000;
};

struct StationLinkCounters {
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
  std::uint64_t live_sent = 0;
  std::uint64_t live_dropped = 0;
  std::uint64_t resend_requests = 0;
  std::uint64_t send_errors = 0;
};

class StationLink {
 public:
  StationLink(ports::LinkPort& port, StationLinkStorage storage, const StationLinkConfig& config);

  // Takes the session's current mesh as version 1. resource_exhausted: the shadow
  // or buffer storage is smaller than the mesh's capacity / link::kMaxFrameBytes * 4.
  Status start(const input::SculptSession& session);

  // One step (never blocks): reads the bridge's requests, publishes a new commit,
  // continues a full send, sends the live stroke and status, flushes.
  void poll(const input::SculptSession& session, ports::TimestampUs now_us);

  bool connected() const { return connected_; }
  std::uint32_t mesh_version() const { return version_; }
  // Bytes waiting for the port (0 = everything handed to the peer).
  std::size_t pending_bytes() const { return out_size_; }
  bool idle() const { return out_size_ == 0 && !full_active_ && !full_wanted_; }
  // A peer said hello and everything it needs has been handed to the port.
  bool peer_synced() const { return connected_ && peer_hello_ && idle(); }
  const StationLinkCounters& counters() const { return counters_; }
  link::DecoderCounters decoder_counters() const { return decoder_.counters(); }

 private:
  enum class FullPhase : std::uint8_t { begin, vertices, triangles, end };

  void receive();
  void on_message(const link::LinkMessage& m);
  void track_mesh(const mesh::Mesh& mesh);
  bool queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                    std::uint32_t old_triangles);
  void continue_full();
  void send_live(const input::SculptSession& session, ports::TimestampUs now_us);
  void send_status(const input::SculptSession& session, ports::TimestampUs now_us);
  std::size_t room() const { return out_.size() - out_size_; }
  bool queue(const link::LinkMessage& m);
  void flush();

  ports::LinkPort& port_;
  StationLinkStorage storage_;
  StationLinkConfig config_;
  mesh::Mesh shadow_;
  link::LinkDecoder decoder_;
  link::LinkMessage scratch_{};  // one message being built (large: kept off the stack)
  std::span<std::byte> out_;
  std::size_t out_size_ = 0;
  bool started_ = false;
  bool connected_ = false;
  bool peer_hello_ = false;
  std::uint32_t version_ = 0;
  std::uint32_t last_sequence_ = 0;
  // Full send in progress (from the shadow).
  bool full_wanted_ = false;
  bool full_active_ = false;
  FullPhase full_phase_ = FullPhase::begin;
  std::size_t full_next_ = 0;
  // Live stroke.
  bool live_was_active_ = false;
  std::uint32_t stroke_ = 0;
  std::array<math::Frame, link::kLinkHands> live_start_{};
  ports::TimestampUs last_live_us_ = 0;
  ports::TimestampUs last_status_us_ = 0;
  bool status_sent_ = false;
  StationLinkCounters counters_{};
};

}  // namespace twister::station
