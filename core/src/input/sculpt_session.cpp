#include "twister/input/sculpt_session.hpp"

#include <bit>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace twister::input {
namespace {

journal::JournalPose to_journal(const math::Frame& f) { return {f.origin, f.u, f.v}; }

SessionEventKind event_for(ActionKind kind) {
  switch (kind) {
    case ActionKind::tracking_lost:
      return SessionEventKind::tracking_lost;
    case ActionKind::tracking_resumed:
      return SessionEventKind::tracking_resumed;
    case ActionKind::refused:
      return SessionEventKind::refused;
    default:
      return SessionEventKind::radius_changed;
  }
}

}  // namespace

SculptSession::SculptSession(const SculptSessionConfig& config, mesh::Mesh& mesh,
                             SculptStorage storage, journal::JournalWriter* journal)
    : config_(config),
      mesh_(mesh),
      storage_(storage),
      journal_(journal),
      buttons_(config.debounce, config.buttons),
      machine_(config.interaction),
      plan_(storage.plan),
      history_(storage.undo_changes, storage.undo_entries),
      mover_(poses_) {
  TWISTER_ASSERT(storage.live_x.size() >= mesh.vertex_capacity() &&
                 storage.live_y.size() >= mesh.vertex_capacity() &&
                 storage.live_z.size() >= mesh.vertex_capacity());
}

Status SculptSession::feed_button(const ports::ButtonEdge& edge) { return buttons_.feed(edge); }

Status SculptSession::set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world) {
  return poses_.set_hand(hand, valid, pose_in_world);
}

bool SculptSession::busy() const { return stroke_mask_ != 0 || mover_.moving(); }

math::ConstVertexColumns SculptSession::rest() const {
  const mesh::Mesh& m = mesh_;
  return {m.x(), m.y(), m.z()};
}

math::VertexColumns SculptSession::live_columns() {
  const std::size_t n = mesh_.vertex_count();
  return {storage_.live_x.first(n), storage_.live_y.first(n), storage_.live_z.first(n)};
}

std::size_t SculptSession::plan_frames(std::array<math::Frame, 2>& frames) const {
  std::size_t n = 0;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((stroke_mask_ & (1u << h)) != 0) frames[n++] = poses_.hand_in_object(h);
  }
  return n;
}

Status SculptSession::begin_segment(std::uint8_t hand_mask) {
  stroke_mask_ = hand_mask;
  std::array<math::Frame, 2> frames{};
  const std::size_t n = plan_frames(frames);
  stroke_radius_m_ = static_cast<double>(machine_.radius_m());
  const Status s =
      plan_.build(rest(), std::span(frames).first(n), stroke_radius_m_, config_.method);
  if (!s.ok()) {
    stroke_mask_ = 0;
    plan_.reset();
    return s;
  }
  chain_step_ = 0;
  stroke_start_ = frames;
  return plan_.apply(rest(), live_columns());
}

Status SculptSession::update_plan() {
  std::array<math::Frame, 2> frames{};
  const std::size_t n = plan_frames(frames);
  TWISTER_TRY(plan_.update(std::span(frames).first(n)));
  return plan_.apply(rest(), live_columns());
}

void SculptSession::journal_append(journal::JournalRecord& record, SessionEvents* out) {
  record.sequence = next_sequence_++;
  if (journal_ == nullptr) return;
  const Status s = journal_->append(record);
  if (!s.ok() && out != nullptr) {
    out->push({SessionEventKind::journal_failed, 0, Reason::none, s, record.sequence});
  }
}

Status SculptSession::commit_plan(const journal::JournalRecord& record, bool journaled,
                                  SessionEvents* out) {
  TWISTER_TRY(plan_.apply(rest(), live_columns()));
  const math::VertexColumns live = live_columns();
  history_.begin_entry();
  bool undoable = true;
  for (const std::uint32_t i : plan_.indices()) {
    const glm::vec3 after{live.x[i], live.y[i], live.z[i]};
    if (!history_.record(i, mesh_.position(i), after).ok()) undoable = false;
    mesh_.set_position(i, after);
  }
  if (!history_.end_entry().ok()) undoable = false;
  if (!undoable && out != nullptr) {
    out->push({SessionEventKind::history_overflow, 0, Reason::none,
               Status(StatusCode::resource_exhausted), next_sequence_});
  }
  if (journaled) {
    journal::JournalRecord copy = record;
    journal_append(copy, out);
  }
  return ok_status();
}

SessionEvent SculptSession::commit_segment(std::uint8_t hand, Reason reason, SessionEvents& out) {
  update_plan().ignore();  // on error the previous update stays in force
  journal::JournalRecord r;
  r.type = journal::RecordType::stroke;
  r.stroke.method = static_cast<std::uint8_t>(plan_.method());
  r.stroke.hand_mask = stroke_mask_;
  r.stroke.chain_step = chain_step_;
  r.stroke.radius_m = stroke_radius_m_;
  std::size_t i = 0;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((stroke_mask_ & (1u << h)) == 0) continue;
    r.stroke.start[h] = to_journal(stroke_start_[i]);
    r.stroke.end[h] = to_journal(plan_.end_frame(i));
    ++i;
  }
  const std::uint32_t sequence = next_sequence_;
  const Status s = commit_plan(r, true, &out);
  const SessionEvent committed{SessionEventKind::committed, hand, reason, s, sequence};
  out.push(committed);
  return committed;
}

void SculptSession::end_hands(std::uint8_t mask, Status status, SessionEvents& out) {
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((mask & (1u << h)) != 0)
      out.push({SessionEventKind::cancelled, h, Reason::none, status, 0});
  }
}

void SculptSession::restart_without(std::uint8_t hand, bool commit, SessionEvents& out) {
  auto remaining = static_cast<std::uint8_t>(stroke_mask_ & ~(1u << hand));
  if (commit) {
    SessionEvent committed = commit_segment(hand, Reason::released, out);
    // The other hands of this segment released in the same step end with this very
    // commit (their own commit actions then find nothing open).
    const auto together = static_cast<std::uint8_t>(remaining & releasing_mask_);
    for (std::uint8_t h = 0; h < kHandCount; ++h) {
      if ((together & (1u << h)) == 0) continue;
      committed.hand = h;
      out.push(committed);
    }
    remaining = static_cast<std::uint8_t>(remaining & ~together);
  } else {
    out.push({SessionEventKind::cancelled, hand, Reason::tracking_timeout, ok_status(), 0});
  }
  stroke_mask_ = 0;
  plan_.reset();
  if (remaining == 0) return;
  const Status s = begin_segment(remaining);
  if (!s.ok()) {
    end_hands(remaining, s, out);
  }
}

void SculptSession::apply_action(const Action& a, SessionEvents& out) {
  const auto bit = static_cast<std::uint8_t>(1u << a.hand);
  switch (a.kind) {
    case ActionKind::grab_begin: {
      std::uint8_t mask = bit;
      if (stroke_mask_ != 0) {
        // A hand joins: what the other hand did so far is committed, then both
        // continue as one two-hand segment from the current poses. Hands grabbing
        // in the same step simply start together.
        mask = static_cast<std::uint8_t>(mask | stroke_mask_);
        if (segment_moved_ || chain_step_ != 0) commit_segment(a.hand, Reason::none, out);
        stroke_mask_ = 0;
        plan_.reset();
      }
      const Status s = begin_segment(mask);
      if (s.ok()) {
        out.push({SessionEventKind::grab_begin, a.hand, Reason::none, s, 0});
      } else {
        out.push({SessionEventKind::refused, a.hand, Reason::none, s, 0});
        const auto previous = static_cast<std::uint8_t>(mask & ~bit);
        if (previous != 0) {
          const Status again = begin_segment(previous);
          if (!again.ok()) end_hands(previous, again, out);
        }
      }
      segment_moved_ = false;
      return;
    }
    case ActionKind::freeze:
      if ((stroke_mask_ & bit) == 0) return;
      commit_segment(a.hand, Reason::none, out);
      {
        std::array<math::Frame, 2> frames{};
        const std::size_t n = plan_frames(frames);
        const Status rebased = plan_.rebase(std::span(frames).first(n));
        if (rebased.ok()) {
          stroke_start_ = frames;
          ++chain_step_;
        } else {
          // Cannot continue with the same weights: end the stroke cleanly.
          const std::uint8_t mask = stroke_mask_;
          stroke_mask_ = 0;
          plan_.reset();
          end_hands(mask, rebased, out);
        }
      }
      segment_moved_ = false;
      return;
    case ActionKind::commit:
      if ((stroke_mask_ & bit) != 0) restart_without(a.hand, true, out);
      segment_moved_ = false;
      return;
    case ActionKind::cancel:
      if ((stroke_mask_ & bit) != 0) restart_without(a.hand, false, out);
      segment_moved_ = false;
      return;
    case ActionKind::move_begin:
      mover_.begin(a.hand);
      out.push({SessionEventKind::move_begin, a.hand, Reason::none, ok_status(), 0});
      return;
    case ActionKind::move_commit: {
      const Result<ObjectMove> move = mover_.commit();
      if (!move.ok()) return;
      journal::JournalRecord r;
      r.type = journal::RecordType::object_move;
      r.move.hand = a.hand;
      r.move.object_before = to_journal(move->before);
      r.move.object_after = to_journal(move->after);
      history_.begin_entry();
      history_.record_object(move->before, move->after);
      history_.end_entry().ignore();  // an object-only entry always fits
      const std::uint32_t sequence = next_sequence_;
      journal_append(r, &out);
      out.push({SessionEventKind::move_committed, a.hand, Reason::released, ok_status(), sequence});
      return;
    }
    case ActionKind::move_cancel:
      if (!mover_.cancel()) return;
      out.push({SessionEventKind::move_cancelled, a.hand, a.reason, ok_status(), 0});
      return;
    case ActionKind::radius_begin:
    case ActionKind::radius_end:
      return;
    case ActionKind::radius_change:
    case ActionKind::tracking_lost:
    case ActionKind::tracking_resumed:
    case ActionKind::refused:
      out.push({event_for(a.kind), a.hand, a.reason, ok_status(), 0});
      return;
  }
}

SessionEvents SculptSession::step(ports::TimestampUs now_us) {
  SessionEvents out;
  buttons_.poll(now_us);
  InteractionInputs inputs;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    inputs.hands[h].pose_valid = poses_.valid(h);
    inputs.hands[h].position_m = glm::vec3(poses_.hand_in_world(h).origin);
    inputs.hands[h].buttons = buttons_.hand(h);
  }
  const ActionList actions = machine_.step(inputs, now_us);
  releasing_mask_ = 0;
  for (const Action& a : actions.items()) {
    if (a.kind == ActionKind::commit) releasing_mask_ |= static_cast<std::uint8_t>(1u << a.hand);
  }
  for (const Action& a : actions.items()) apply_action(a, out);
  mover_.follow();
  if (stroke_mask_ != 0) {
    update_plan().ignore();
    segment_moved_ = true;
  }
  return out;
}

LiveWarp SculptSession::live() const {
  LiveWarp w;
  w.active = stroke_mask_ != 0;
  w.hand_mask = stroke_mask_;
  w.plan = &plan_;
  const std::size_t n = mesh_.vertex_count();
  w.positions = {storage_.live_x.first(n), storage_.live_y.first(n), storage_.live_z.first(n)};
  return w;
}

}  // namespace twister::input
