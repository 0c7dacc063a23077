// StationLink: the live stream on the urgent queue. `hands` at the tracker rate
// (when a pose, a button, the radius or the stroke changed; at most one per
// live_interval_us), `stroke` when a segment starts and about once a second while it
// lasts, `object` when the object pose changed, `status` once a second and when
// something in it changed.
#include <algorithm>
#include <cstring>

#include "twister/link/math_conversion.hpp"
#include "twister/station/station_link.hpp"

namespace twister::station {
namespace {

bool same_frame(const math::Frame& a, const math::Frame& b) {
  return a.origin == b.origin && a.u == b.u && a.v == b.v && a.w == b.w;
}

bool same_hands(const link::Hands& a, const link::Hands& b) {
  if (a.stroke != b.stroke || a.flags != b.flags || a.buttons != b.buttons ||
      a.radius_m != b.radius_m) {
    return false;
  }
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if (a.hands[h].position != b.hands[h].position || a.hands[h].rotation != b.hands[h].rotation) {
      return false;
    }
  }
  return true;
}

std::uint8_t button_bits(const input::HandButtons& b) {
  return static_cast<std::uint8_t>(
      (b.grab ? link::kButtonGrab : 0) | (b.radius ? link::kButtonRadius : 0) |
      (b.freeze ? link::kButtonFreeze : 0) | (b.move_object ? link::kButtonMoveObject : 0));
}

}  // namespace

void StationLink::send_live(const session::SculptSession& session, const StationStatus& status,
                            ports::TimestampUs now_us) {
  const session::LiveWarp live = session.live();
  const bool active = live.active && live.plan != nullptr && live.plan->built();
  if (active) {
    bool new_segment = !live_was_active_;
    for (std::size_t k = 0; k < live.plan->hand_count() && k < link::kLinkHands; ++k) {
      new_segment = new_segment || !same_frame(live.plan->start_frame(k), live_start_[k]);
      live_start_[k] = live.plan->start_frame(k);
    }
    if (new_segment) ++stroke_;
    if (new_segment || now_us - last_stroke_us_ >= config_.stroke_repeat_us) {
      send_stroke(live, now_us);
    }
  }
  live_was_active_ = active;
  send_object(session);
  // At the tracker rate: a new pose changes the update; an unchanged one is not sent.
  if (!hands_sent_ || now_us - last_live_us_ >= config_.live_interval_us) {
    send_hands(session, active ? live : session::LiveWarp{});
    last_live_us_ = now_us;
  }
  send_status(session, status, now_us);
}

void StationLink::send_stroke(const session::LiveWarp& live, ports::TimestampUs now_us) {
  const math::WarpPlan& plan = *live.plan;
  link::StrokeBegin& s = scratch_.stroke;
  scratch_.type = link::MessageType::stroke;
  s = link::StrokeBegin{};
  s.stroke = stroke_;
  s.mesh_version = version_;
  s.method = static_cast<std::uint8_t>(plan.method());
  s.hand_mask = live.hand_mask;
  s.radius_m = plan.radius();
  std::size_t k = 0;
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if ((live.hand_mask & (1u << h)) == 0 || k >= plan.hand_count()) continue;
    s.start[h] = link::to_wire(plan.start_frame(k++));
  }
  if (queue_urgent(scratch_)) last_stroke_us_ = now_us;
}

void StationLink::send_hands(const session::SculptSession& session, const session::LiveWarp& live) {
  link::Hands l;
  l.stroke = static_cast<std::uint16_t>(stroke_);
  l.radius_m = session.radius_m();
  if (live.active) l.flags = link::kStrokeActive;
  std::size_t k = 0;  // plan hand of session hand h
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    const auto hand = static_cast<std::uint8_t>(h);
    const bool tracked = session.poses().valid(hand);
    const bool in_stroke = live.active && (live.hand_mask & (1u << h)) != 0;
    l.buttons =
        static_cast<std::uint8_t>(l.buttons | button_bits(session.hand_buttons(hand)) << (4 * h));
    if (tracked) l.flags = static_cast<std::uint8_t>(l.flags | (link::kHandTracked0 << h));
    if (in_stroke && k < live.plan->hand_count()) {
      l.hands[h] = link::to_live_compact(live.plan->start_frame(k), live.plan->end_frame(k),
                                         live.plan->screw(k));
      ++k;
    } else if (tracked) {
      l.hands[h] = link::to_compact(session.poses().hand_in_object(hand));
    } else {
      continue;
    }
    l.flags = static_cast<std::uint8_t>(l.flags | (link::kHandSample0 << h));
  }
  if (hands_sent_ && same_hands(l, last_hands_)) return;  // nothing new to show
  l.sequence = hands_sequence_;
  scratch_.type = link::MessageType::hands;
  scratch_.hands = l;
  if (!queue_urgent(scratch_)) {
    ++counters_.live_dropped;  // the next update replaces it
    return;
  }
  ++hands_sequence_;
  ++counters_.live_sent;
  last_hands_ = l;
  hands_sent_ = true;
}

void StationLink::send_object(const session::SculptSession& session) {
  const math::Frame& pose = session.object_pose();
  if (object_sent_valid_ && same_frame(pose, object_sent_)) return;
  scratch_.type = link::MessageType::object;
  scratch_.object.pose = link::to_compact(pose);
  if (!queue_urgent(scratch_)) return;  // tried again next poll
  object_sent_ = pose;
  object_sent_valid_ = true;
}

void StationLink::send_status(const session::SculptSession& session, const StationStatus& status,
                              ports::TimestampUs now_us) {
  link::StatusReport s;
  const mesh::Mesh& mesh = session.mesh();
  s.mesh_version = version_;
  s.vertex_count = static_cast<std::uint32_t>(mesh.vertex_count());
  s.vertex_capacity = static_cast<std::uint32_t>(mesh.vertex_capacity());
  s.triangle_count = static_cast<std::uint32_t>(mesh.triangle_count());
  s.triangle_capacity = static_cast<std::uint32_t>(mesh.triangle_capacity());
  s.tracker_state = static_cast<std::uint8_t>(status.tracker);
  s.tracker_rate_hz = status.tracker_rate_hz;
  s.method = static_cast<std::uint8_t>(status.method);
  s.clutch = status.clutch;
  s.turned_rad = status.turned_rad;
  s.turn_limit_rad = status.turn_limit_rad;
  s.strokes_committed = status.strokes_committed;
  s.strokes_not_saved = status.strokes_not_saved;
  s.capacity_stops = status.capacity_stops;
  const bool changed = s.tracker_state != last_status_.tracker_state ||
                       s.strokes_not_saved != last_status_.strokes_not_saved ||
                       s.capacity_stops != last_status_.capacity_stops ||
                       s.turn_limit_rad != last_status_.turn_limit_rad ||
                       s.method != last_status_.method || s.clutch != last_status_.clutch ||
                       s.mesh_version != last_status_.mesh_version;
  if (status_sent_ && !changed && now_us - last_status_us_ < config_.status_interval_us) return;
  const link::DecoderCounters d = decoder_.counters();
  s.live_sent = counters_.live_sent;
  s.live_dropped = counters_.live_dropped;
  s.frames_rejected = d.bad_crc + d.bad_cobs + d.bad_payload;
  scratch_.type = link::MessageType::status;
  scratch_.status = s;
  if (!queue_urgent(scratch_)) return;
  status_sent_ = true;
  last_status_ = s;
  last_status_us_ = now_us;
}

}  // namespace twister::station
