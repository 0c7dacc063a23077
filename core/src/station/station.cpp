#include "twister/station/station.hpp"

#include <algorithm>
#include <cmath>

namespace twister::station {
namespace {

// Bounds per poll() so one chatty source cannot starve the others or the loop.
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
      tracker_(tracker, clock, config_),
      writer_(storage),
      sculpt_(config.sculpt, mesh, work, &writer_),
      checkpoints_(files.checkpoint_out, config.checkpoint_interval,
                   config.checkpoint_bytes_per_poll),
      exhibit_(config.exhibit) {}

void Station::emit(session::SessionEvent event, ports::TimestampUs now_us) {
  event.time_us = now_us;
  counters_.events.count(event);
  if (!events_.push(event)) ++counters_.events.events_dropped;
}

void Station::emit_all(const session::SessionEvents& events, ports::TimestampUs now_us) {
  counters_.events.session_events_dropped += events.dropped();
  for (const session::SessionEvent& e : events.items()) emit(e, now_us);
}

void Station::drain_buttons(ports::TimestampUs now_us) {
  Status why = StatusCode::unavailable;  // not there (at start-up)
  for (int i = 0; i < kMaxEdgesPerPoll && buttons_.connected(); ++i) {
    auto edge = buttons_.poll();
    if (edge.ok()) {
      ++counters_.input.button_edges;
      exhibit_.feed_edge(*edge);
      if (!sculpt_.feed_button(*edge).ok()) ++counters_.input.button_errors;
      continue;
    }
    if (edge.status().code() == StatusCode::unavailable) break;
    ++counters_.input.button_errors;
    why = edge.status();  // io_error: it vanished
    break;
  }
  // The device going or coming: one event each way (the first poll reports one
  // missing at start-up), and the session's strokes follow (lost-tracking path).
  const bool connected = buttons_.connected();
  if (connected == sculpt_.buttons_connected()) return;
  sculpt_.set_buttons_connected(connected);
  emit(connected ? session::make_event(session::SessionEventKind::buttons_found, 0)
                 : session::make_event(session::SessionEventKind::buttons_lost, 0, {}, why),
       now_us);
}

Status Station::poll() {
  if (!started_) return StatusCode::failed_precondition;
  const ports::TimestampUs now_us = clock_.now_us();
  StylusEdges stylus;
  if (auto change = tracker_.drain(now_us, stylus, counters_.input)) emit(*change, now_us);
  for (const ports::ButtonEdge& edge : stylus.items()) {
    exhibit_.feed_edge(edge);
    if (!sculpt_.feed_button(edge).ok()) ++counters_.input.button_errors;
  }
  drain_buttons(now_us);
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    const bool valid = tracker_.hand_valid(h, now_us);
    // invalid_argument: not orthonormal; the session then treats the hand as lost.
    if (!sculpt_.set_hand(h, valid, tracker_.hand_pose(h)).ok()) {
      ++counters_.input.pose_errors;
    }
  }
  emit_all(sculpt_.step(now_us), now_us);
  step_exhibit(now_us);
  if (auto done = checkpoints_.step(sculpt_, checkpoint_anchor())) emit(*done, now_us);
  counters_.checkpoints_restarted = checkpoints_.restarted();
  return ok_status();
}

StationStatus Station::status() const {
  StationStatus s;
  s.tracker = tracker_.link_state();
  if (s.tracker == TrackerLinkState::streaming) s.tracker_rate_hz = tracker_.rate_hz();
  s.strokes_committed = counters_.events.strokes_committed;
  s.strokes_not_saved = counters_.events.strokes_not_saved;
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
  s.buttons_missing = !sculpt_.buttons_connected();
  return s;
}

void Station::stop() {
  if (!started_) return;
  const ports::TimestampUs now_us = clock_.now_us();
  emit_all(sculpt_.cancel_open(), now_us);
  if (auto done = checkpoints_.finish(sculpt_, checkpoint_anchor())) emit(*done, clock_.now_us());
}

Status Station::flush() { return storage_.sync(); }

}  // namespace twister::station
