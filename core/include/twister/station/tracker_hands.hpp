// TrackerHands: the Fastrak session seen as two hands. drain() reads the tracker's
// poses (at most kMaxPosesPerPoll a pass, so a chatty tracker cannot starve the
// loop), converts those of the receivers the hands hold into station frames (metres,
// world), turns the stylus switch into button edges for the session, counts poses and
// reports the tracker going up or down (tracker_streaming, tracker_lost). A hand is
// valid only while the tracker streams and its pose is fresh: after a loss no pose
// from before it counts, so an unplug never moves a hand. Also the tracker's rate
// (poses used per second, over windows of about a second). No heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/session_events.hpp"
#include "twister/station/station_config.hpp"
#include "twister/station/station_counters.hpp"
#include "twister/station/station_status.hpp"
#include "twister/tracker/fastrak_session.hpp"

namespace twister::station {

inline constexpr std::size_t kMaxPosesPerPoll = 64;

// The stylus edges of one drain(), in the order their records came.
class StylusEdges {
 public:
  void push(const ports::ButtonEdge& edge);
  std::span<const ports::ButtonEdge> items() const { return items_.span(); }

 private:
  InlineVector<ports::ButtonEdge, kMaxPosesPerPoll> items_;
};

class TrackerHands {
 public:
  // `config` must outlive this (the station's copy).
  TrackerHands(ports::ByteStream& tracker, ports::Clock& clock, const StationConfig& config);

  // One pass over the tracker at `now_us`: poses to hands, stylus edges to `stylus`
  // (each counted as a button edge), poses counted in `counters`. Returns the
  // tracker going up (tracker_streaming) or down (tracker_lost), if it did.
  std::optional<session::SessionEvent> drain(ports::TimestampUs now_us, StylusEdges& stylus,
                                             InputCounters& counters);

  bool hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const;
  // The frame last applied to `hand` (hand < kHandCount).
  const Pose& hand_pose(std::uint8_t hand) const { return hands_[hand].pose; }
  TrackerLinkState link_state() const;
  float rate_hz() const { return rate_hz_; }  // 0 until the first window ends
  const tracker::FastrakSession& session() const { return session_; }

 private:
  struct Hand {
    Pose pose{};
    ports::TimestampUs pose_time_us = 0;
    bool has_pose = false;
  };

  void use_pose(const tracker::FastrakPose& pose, ports::TimestampUs now_us, StylusEdges& stylus,
                InputCounters& counters);
  void update_rate(ports::TimestampUs now_us, const InputCounters& counters);

  const StationConfig& config_;
  tracker::FastrakSession session_;
  std::array<Hand, input::kHandCount> hands_{};
  std::array<bool, tracker::kMaxStations> stylus_down_{};
  bool was_streaming_ = false;
  ports::TimestampUs rate_window_us_ = 0;
  std::uint64_t rate_window_poses_ = 0;
  float rate_hz_ = 0.0F;
};

}  // namespace twister::station
