#include "twister/station/tracker_hands.hpp"

namespace twister::station {

void StylusEdges::push(const ports::ButtonEdge& edge) {
  items_.push_back(edge).ignore();  // at most one per pose: never full
}

TrackerHands::TrackerHands(ports::ByteStream& tracker, ports::Clock& clock,
                           const StationConfig& config)
    : config_(config), session_(tracker, clock, config.session) {}

bool TrackerHands::hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const {
  const Hand& h = hands_[hand];
  return h.has_pose && session_.streaming() && now_us - h.pose_time_us <= config_.pose_stale_us;
}

TrackerLinkState TrackerHands::link_state() const {
  if (session_.streaming()) return TrackerLinkState::streaming;
  return session_.counters().streams_started > 0 ? TrackerLinkState::lost
                                                 : TrackerLinkState::starting;
}

void TrackerHands::use_pose(const tracker::FastrakPose& pose, ports::TimestampUs now_us,
                            StylusEdges& stylus, InputCounters& counters) {
  if (pose.has_button && pose.station >= 1 && pose.station <= tracker::kMaxStations) {
    const auto idx = static_cast<std::size_t>(pose.station - 1);
    const std::int8_t line = config_.stylus_line[idx];
    if (line >= 0 && pose.button != stylus_down_[idx]) {
      stylus_down_[idx] = pose.button;
      ++counters.button_edges;
      stylus.push({static_cast<std::uint8_t>(line), pose.button, now_us});
    }
  }
  int hand = -1;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if (config_.hand_station[h] == pose.station) hand = h;
  }
  if (hand < 0) {
    ++counters.foreign_poses;
    return;
  }
  auto frame = tracker::to_station_frame(pose, config_.conversion);
  if (!frame.ok()) {
    ++counters.pose_errors;  // skip: never let an implausible pose move a hand
    return;
  }
  Hand& h = hands_[static_cast<std::size_t>(hand)];
  h.pose = *frame;
  h.pose_time_us = now_us;
  h.has_pose = true;
  ++counters.poses;
}

std::optional<session::SessionEvent> TrackerHands::drain(ports::TimestampUs now_us,
                                                         StylusEdges& stylus,
                                                         InputCounters& counters) {
  for (std::size_t i = 0; i < kMaxPosesPerPoll; ++i) {
    auto pose = session_.poll();
    if (!pose.ok()) break;  // unavailable: nothing now; invalid_argument: bad config
    use_pose(*pose, now_us, stylus, counters);
  }
  update_rate(now_us, counters);
  const bool streaming = session_.streaming();
  if (streaming == was_streaming_) return std::nullopt;
  was_streaming_ = streaming;
  if (streaming) {
    return session::make_event(
        session::SessionEventKind::tracker_streaming, 0,
        session::payload::TrackerStreaming{session_.counters().streams_started});
  }
  // Poses from before a loss must not count as valid after re-initialisation. A
  // stylus held at the loss stays "held": no release is invented, so the session
  // holds the stroke and cancels it after lost_timeout instead of committing it;
  // the first record after re-plug brings the true state.
  for (auto& h : hands_) h.has_pose = false;
  return session::make_event(session::SessionEventKind::tracker_lost, 0);
}

void TrackerHands::update_rate(ports::TimestampUs now_us, const InputCounters& counters) {
  if (now_us - rate_window_us_ < 1'000'000) return;
  const double seconds = static_cast<double>(now_us - rate_window_us_) / 1e6;
  rate_hz_ = static_cast<float>(static_cast<double>(counters.poses - rate_window_poses_) / seconds);
  rate_window_us_ = now_us;
  rate_window_poses_ = counters.poses;
}

}  // namespace twister::station
