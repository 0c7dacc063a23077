#include "twister/station/station.hpp"

#include <algorithm>
#include <cmath>

namespace twister::station {
namespace {

// Bounds per poll() so one chatty source cannot starve the others or the loop.
constexpr int kMaxPosesPerPoll = 64;
constexpr int kMaxEdgesPerPoll = 32;

}  // namespace

Station::Station(ports::ByteStream& tracker, ports::ButtonSource& buttons, ports::Clock& clock,
                 ports::Storage& storage, mesh::Mesh& mesh, session::SculptStorage work,
                 const StationConfig& config, StationFiles files)
    : buttons_(buttons),
      clock_(clock),
      storage_(storage),
      files_(files),
      config_(config),
      session_(tracker, clock, config.session),
      writer_(storage),
      sculpt_(config.sculpt, mesh, work, &writer_),
      checkpoint_(files.checkpoint_out) {}

bool Station::hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const {
  const Hand& h = hands_[hand];
  return h.has_pose && session_.streaming() && now_us - h.pose_time_us <= config_.pose_stale_us;
}

void Station::drain_tracker(ports::TimestampUs now_us) {
  for (int i = 0; i < kMaxPosesPerPoll; ++i) {
    auto pose = session_.poll();
    if (!pose.ok()) break;  // unavailable: nothing now; invalid_argument: bad config
    if (pose->has_button && pose->station >= 1 && pose->station <= tracker::kMaxStations) {
      const auto idx = static_cast<std::size_t>(pose->station - 1);
      const std::int8_t line = config_.stylus_line[idx];
      if (line >= 0 && pose->button != stylus_down_[idx]) {
        stylus_down_[idx] = pose->button;
        ++counters_.button_edges;
        const ports::ButtonEdge edge{static_cast<std::uint8_t>(line), pose->button, now_us};
        if (!sculpt_.feed_button(edge).ok()) ++counters_.button_errors;
      }
    }
    int hand = -1;
    for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
      if (config_.hand_station[h] == pose->station) hand = h;
    }
    if (hand < 0) {
      ++counters_.foreign_poses;
      continue;
    }
    auto frame = tracker::to_station_frame(*pose, config_.conversion);
    if (!frame.ok()) {
      ++counters_.pose_errors;  // skip: never let an implausible pose move a hand
      continue;
    }
    Hand& h = hands_[static_cast<std::size_t>(hand)];
    h.pose = *frame;
    h.pose_time_us = now_us;
    h.has_pose = true;
    ++counters_.poses;
  }
  const bool streaming = session_.streaming();
  if (streaming != was_streaming_) {
    was_streaming_ = streaming;
    // Poses from before a loss must not count as valid after re-initialisation. A
    // stylus held at the loss stays "held": no release is invented, so the session
    // holds the stroke and cancels it after lost_timeout instead of committing it;
    // the first record after re-plug brings the true state.
    if (!streaming) {
      for (auto& h : hands_) h.has_pose = false;
    }
    push_event({streaming ? StationEventKind::tracker_streaming : StationEventKind::tracker_lost, 0,
                0, session_.counters().streams_started, ok_status(), now_us});
  }
}

void Station::drain_buttons(ports::TimestampUs now_us) {
  for (int i = 0; i < kMaxEdgesPerPoll; ++i) {
    auto edge = buttons_.poll();
    if (edge.ok()) {
      buttons_failed_ = false;
      ++counters_.button_edges;
      if (!sculpt_.feed_button(*edge).ok()) ++counters_.button_errors;
      continue;
    }
    if (edge.status().code() == StatusCode::unavailable) break;
    ++counters_.button_errors;
    if (!buttons_failed_) {
      push_event({StationEventKind::button_source_error, 0, 0, 0, edge.status(), now_us});
    }
    buttons_failed_ = true;
    break;
  }
}

Status Station::poll() {
  if (!started_) return StatusCode::failed_precondition;
  const ports::TimestampUs now_us = clock_.now_us();
  drain_tracker(now_us);
  drain_buttons(now_us);
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    const bool valid = hand_valid(h, now_us);
    // invalid_argument: not orthonormal; the session then treats the hand as lost.
    if (!sculpt_.set_hand(h, valid, hands_[h].pose).ok()) ++counters_.pose_errors;
  }
  const session::SessionEvents events = sculpt_.step(now_us);
  counters_.session_events_dropped += events.dropped();
  for (const session::SessionEvent& e : events.items()) report(e, now_us);
  checkpoint_step();
  if (now_us - rate_window_us_ >= 1'000'000) {
    const double seconds = static_cast<double>(now_us - rate_window_us_) / 1e6;
    rate_hz_ =
        static_cast<float>(static_cast<double>(counters_.poses - rate_window_poses_) / seconds);
    rate_window_us_ = now_us;
    rate_window_poses_ = counters_.poses;
  }
  return ok_status();
}

StationStatus Station::status() const {
  StationStatus s;
  if (session_.streaming()) {
    s.tracker = TrackerLinkState::streaming;
    s.tracker_rate_hz = rate_hz_;
  } else if (session_.counters().streams_started > 0) {
    s.tracker = TrackerLinkState::lost;
  }
  s.strokes_committed = counters_.strokes_committed;
  s.strokes_not_saved = counters_.strokes_not_saved;
  const session::SessionState& state = sculpt_.state();
  s.method = state.method;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    const session::HandView& v = state.hands[h];
    if (v.in_stroke && !v.engaged) s.clutch |= static_cast<std::uint8_t>(1u << h);
    if (v.in_stroke)
      s.turned_rad = std::max(s.turned_rad, static_cast<float>(std::abs(v.turn_rad)));
    s.turn_limit_rad = std::max(s.turn_limit_rad, static_cast<float>(v.turn_limit_rad));
  }
  s.capacity_stops = state.refine.capacity_stops;
  return s;
}

void Station::report(const session::SessionEvent& e, ports::TimestampUs now_us) {
  using K = session::SessionEventKind;
  const auto reason = static_cast<std::uint64_t>(e.reason);
  switch (e.kind) {
    case K::grab_begin:
      push_event({StationEventKind::stroke_begin, e.hand, 0, 0, ok_status(), now_us});
      break;
    case K::committed:
      // One commit, however many hands it ends (repeat: already counted).
      if (!e.repeat && e.status.ok()) ++counters_.strokes_committed;
      push_event(
          {StationEventKind::stroke_committed, e.hand, e.sequence, reason, e.status, now_us});
      break;
    case K::cancelled:
      ++counters_.strokes_cancelled;
      push_event({StationEventKind::stroke_cancelled, e.hand, 0, reason, e.status, now_us});
      break;
    case K::refused:
      ++counters_.refused;
      push_event({StationEventKind::refused, e.hand, 0, reason, e.status, now_us});
      break;
    case K::not_saved:
      // One commit not made, however many hands it ends (repeat: already counted).
      if (!e.repeat) {
        ++counters_.strokes_not_saved;
        ++counters_.journal_errors;
      }
      push_event(
          {StationEventKind::stroke_not_saved, e.hand, e.sequence, reason, e.status, now_us});
      break;
    default:
      report_sculpt(e, now_us);
      break;
  }
}

void Station::report_sculpt(const session::SessionEvent& e, ports::TimestampUs now_us) {
  using K = session::SessionEventKind;
  StationEvent out{StationEventKind::radius_set, e.hand, e.sequence, 0, e.status, now_us, e.value};
  switch (e.kind) {
    case K::radius_set:
      break;
    case K::disengaged:
      out.kind = StationEventKind::hand_disengaged;
      break;
    case K::engaged:
      out.kind = StationEventKind::hand_engaged;
      break;
    case K::turn_limit_reached:
      out.kind = StationEventKind::turn_limit_reached;
      break;
    case K::turn_limit_left:
      out.kind = StationEventKind::turn_limit_left;
      break;
    case K::undone:
      ++counters_.undos;
      out.kind = StationEventKind::undone;
      break;
    case K::redone:
      ++counters_.redos;
      out.kind = StationEventKind::redone;
      break;
    case K::method_changed:
      out.kind = StationEventKind::method_changed;
      out.value = static_cast<std::uint64_t>(e.value);
      break;
    case K::command_refused:
      // io_error: an undo/redo whose record could not be saved (taken back).
      if (e.status.code() == StatusCode::io_error) ++counters_.journal_errors;
      out.kind = StationEventKind::command_refused;
      out.value = static_cast<std::uint64_t>(e.value);
      out.detail = static_cast<std::uint8_t>(e.reason);
      break;
    case K::refined:
      ++counters_.refined_commits;
      out.kind = StationEventKind::stroke_refined;
      out.value = static_cast<std::uint64_t>(e.value);
      break;
    case K::refine_stopped:
      ++counters_.refine_stops;
      out.kind = StationEventKind::refinement_stopped;
      out.value = static_cast<std::uint64_t>(e.value);
      break;
    default:
      return;  // tracking, each radius change, moves, overflow: in the session's state
  }
  push_event(out);
}

void Station::push_event(const StationEvent& event) {
  if (event_count_ == kEventCapacity) {
    ++counters_.events_dropped;
    return;
  }
  events_[(event_head_ + event_count_) % kEventCapacity] = event;
  ++event_count_;
}

Result<StationEvent> Station::next_event() {
  if (event_count_ == 0) return StatusCode::unavailable;
  const StationEvent e = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_count_;
  return e;
}

void Station::stop() {
  if (!started_) return;
  const ports::TimestampUs now_us = clock_.now_us();
  const session::SessionEvents events = sculpt_.cancel_open();
  for (const session::SessionEvent& e : events.items()) {
    if (e.kind != session::SessionEventKind::cancelled) continue;
    ++counters_.strokes_cancelled;
    push_event({StationEventKind::stroke_cancelled, e.hand, 0,
                static_cast<std::uint64_t>(input::Reason::none), ok_status(), now_us});
  }
  final_checkpoint();
}

Status Station::flush() { return storage_.sync(); }

}  // namespace twister::station
