// LiveStream: hands, stroke, object and status on the urgent queue.
#include "twister/station/station_link_live.hpp"

#include <algorithm>

#include "twister/link/math_conversion.hpp"

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

void LiveStream::restart() {
  workspace_sent_ = false;
  hands_.sent = false;
  status_.sent = false;
  object_.valid = false;
  stroke_.last_us = 0;
  stroke_.was_active = false;
}

void LiveStream::poll(const session::SculptSession& session, const StationStatus& status,
                      const LinkFacts& facts, ports::TimestampUs now_us) {
  if (!workspace_sent_) workspace_sent_ = out_.urgent(config_.workspace);  // else next poll
  const session::LiveWarp live = session.live();
  const bool active = live.active && live.plan != nullptr && live.plan->built();
  if (active) {
    bool new_segment = !stroke_.was_active;
    for (std::size_t k = 0; k < live.plan->hand_count() && k < link::kLinkHands; ++k) {
      new_segment = new_segment || !same_frame(live.plan->start_frame(k), stroke_.start[k]);
      stroke_.start[k] = live.plan->start_frame(k);
    }
    if (new_segment) ++stroke_.id;
    if (new_segment || now_us - stroke_.last_us >= config_.stroke_repeat_us) {
      send_stroke(live, facts.mesh_version, now_us);
    }
  }
  stroke_.was_active = active;
  send_object(session);
  // At the tracker rate: a new pose changes the update; an unchanged one is not sent.
  if (!hands_.sent || now_us - hands_.last_us >= config_.live_interval_us) {
    send_hands(session, active ? live : session::LiveWarp{});
    hands_.last_us = now_us;
  }
  send_status(session, status, facts, now_us);
}

void LiveStream::send_stroke(const session::LiveWarp& live, std::uint32_t mesh_version,
                             ports::TimestampUs now_us) {
  const math::WarpPlan& plan = *live.plan;
  link::StrokeBegin s;
  s.stroke = stroke_.id;
  s.mesh_version = mesh_version;
  s.method = static_cast<std::uint8_t>(plan.method());
  s.hand_mask = live.hand_mask;
  s.radius_m = plan.radius();
  s.refine_threshold_m = static_cast<float>(live.refine_threshold_m);
  const math::SymmetrySpec sym = plan.symmetry();
  s.symmetry = {static_cast<std::uint8_t>(sym.kind), sym.mirrors, sym.axis, sym.order};
  std::size_t k = 0;
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if ((live.hand_mask & (1u << h)) == 0 || k >= plan.hand_count()) continue;
    s.start[h] = plan.start_frame(k++);
  }
  if (out_.urgent(s)) stroke_.last_us = now_us;
}

void LiveStream::send_hands(const session::SculptSession& session, const session::LiveWarp& live) {
  link::Hands l;
  l.stroke = static_cast<std::uint16_t>(stroke_.id);
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
  if (hands_.sent && same_hands(l, hands_.last)) return;  // nothing new to show
  l.sequence = hands_.sequence;
  if (!out_.urgent(l)) {
    ++counters_.live_dropped;  // the next update replaces it
    return;
  }
  ++hands_.sequence;
  ++counters_.live_sent;
  hands_.last = l;
  hands_.sent = true;
}

void LiveStream::send_object(const session::SculptSession& session) {
  const math::Frame& pose = session.object_pose();
  if (object_.valid && same_frame(pose, object_.pose)) return;
  if (!out_.urgent(link::ObjectPose{link::to_compact(pose)})) return;  // tried again next poll
  object_.pose = pose;
  object_.valid = true;
}

void LiveStream::send_status(const session::SculptSession& session, const StationStatus& status,
                             const LinkFacts& facts, ports::TimestampUs now_us) {
  link::StatusReport s;
  const mesh::Mesh& mesh = session.mesh();
  s.mesh_version = facts.mesh_version;
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
  s.strokes.committed = status.strokes_committed;
  s.strokes.not_saved = status.strokes_not_saved;
  s.strokes.capacity_stops = status.capacity_stops;
  s.buttons_state = static_cast<std::uint8_t>(status.buttons_missing ? link::ButtonsState::missing
                                                                     : link::ButtonsState::present);
  s.spectators = static_cast<std::uint8_t>(std::min<std::uint32_t>(facts.spectators, 255));
  const math::SymmetrySpec next = session.symmetry();
  s.symmetry = {static_cast<std::uint8_t>(next.kind), next.mirrors, next.axis, next.order};
  const link::StatusReport& last = status_.last;
  const bool changed = s.tracker_state != last.tracker_state ||
                       s.strokes.not_saved != last.strokes.not_saved ||
                       s.strokes.capacity_stops != last.strokes.capacity_stops ||
                       s.turn_limit_rad != last.turn_limit_rad || s.method != last.method ||
                       s.clutch != last.clutch || s.mesh_version != last.mesh_version ||
                       s.buttons_state != last.buttons_state || s.symmetry != last.symmetry ||
                       s.spectators != last.spectators;
  if (status_.sent && !changed && now_us - status_.last_us < config_.status_interval_us) return;
  s.traffic.live_sent = counters_.live_sent;
  s.traffic.live_dropped = counters_.live_dropped;
  s.traffic.frames_rejected = facts.frames_rejected;
  if (!out_.urgent(s)) return;
  status_.sent = true;
  status_.last = s;
  status_.last_us = now_us;
}

}  // namespace twister::station
