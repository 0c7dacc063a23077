// LiveStream: what the display shows between commits, on the urgent queue.
// `hands` at the tracker rate (when a pose, a button, the radius or the stroke
// changed; at most one per live_interval_us; one that finds no room is dropped and
// counted, the next replaces it), `stroke` when a segment starts and about once a
// second while it lasts (the exact start frames), `object` when the object pose
// changed, `status` once a second and when something in it changed, `workspace`
// once per admission (before anything else). No heap. Not
// thread-safe.
#pragma once

#include <array>
#include <cstdint>

#include "twister/link/link_message.hpp"
#include "twister/math/frame.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_link_queues.hpp"
#include "twister/station/station_status.hpp"

namespace twister::station {

struct LiveStreamConfig {
  ports::TimestampUs live_interval_us = 8'000;  // at most one hands update per interval
  ports::TimestampUs status_interval_us = 1'000'000;
  ports::TimestampUs stroke_repeat_us = 1'000'000;  // stroke message repeated while open
  link::Workspace workspace{};                      // sent once after each admission
};

struct LiveCounters {
  std::uint64_t live_sent = 0;     // hands updates
  std::uint64_t live_dropped = 0;  // hands updates that found no room
};

// Facts of the link itself the status reports.
struct LinkFacts {
  std::uint32_t mesh_version = 0;     // the display's mesh version
  std::uint64_t frames_rejected = 0;  // bad frames from the display
  std::uint32_t spectators = 0;       // read-only displays connected (issue 25)
};

class LiveStream {
 public:
  LiveStream(FrameQueues& out, const LiveStreamConfig& config) : out_(out), config_(config) {}

  // Sends what changed (or is due) since the last poll.
  void poll(const session::SculptSession& session, const StationStatus& status,
            const LinkFacts& facts, ports::TimestampUs now_us);
  // A display was (re)admitted: everything goes again at the next poll.
  void restart();
  // The hands go again at the next poll even if unchanged (a display that just got
  // the mesh an open stroke refers to shows the stroke at once).
  void resend_hands() { hands_.sent = false; }
  const LiveCounters& counters() const { return counters_; }

 private:
  struct StrokeSent {
    bool was_active = false;
    std::uint32_t id = 0;  // +1 per segment
    std::array<math::Frame, link::kLinkHands> start{};
    ports::TimestampUs last_us = 0;
  };
  struct HandsSent {
    bool sent = false;
    std::uint16_t sequence = 0;
    link::Hands last{};
    ports::TimestampUs last_us = 0;
  };
  struct ObjectSent {
    bool valid = false;
    math::Frame pose{};
  };
  struct StatusSent {
    bool sent = false;
    link::StatusReport last{};
    ports::TimestampUs last_us = 0;
  };

  void send_stroke(const session::LiveWarp& live, std::uint32_t mesh_version,
                   ports::TimestampUs now_us);
  void send_hands(const session::SculptSession& session, const session::LiveWarp& live);
  void send_object(const session::SculptSession& session);
  void send_status(const session::SculptSession& session, const StationStatus& status,
                   const LinkFacts& facts, ports::TimestampUs now_us);

  FrameQueues& out_;
  LiveStreamConfig config_;
  StrokeSent stroke_{};
  HandsSent hands_{};
  ObjectSent object_{};
  StatusSent status_{};
  bool workspace_sent_ = false;
  LiveCounters counters_{};
};

}  // namespace twister::station
