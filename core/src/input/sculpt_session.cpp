// SculptSession: the wiring. Each step: buttons -> machine -> actions dispatched to
// the part that owns them (strokes, object move, plain events), then the open move
// and stroke follow the hands. History and replay calls pass straight through.
#include "twister/input/sculpt_session.hpp"

#include <glm/vec3.hpp>

namespace twister::input {
namespace {

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
    : mesh_(mesh, storage.live_x, storage.live_y, storage.live_z),
      buttons_(config.debounce, config.buttons),
      machine_(config.interaction),
      plan_(storage.plan),
      history_(mesh_, poses_, storage.undo_changes, storage.undo_entries, journal),
      strokes_(plan_, mesh_, poses_, history_, config.method),
      mover_(poses_),
      replay_(plan_, mesh_, history_, poses_) {}

Status SculptSession::feed_button(const ports::ButtonEdge& edge) { return buttons_.feed(edge); }

Status SculptSession::set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world) {
  return poses_.set_hand(hand, valid, pose_in_world);
}

SessionEvents SculptSession::step(ports::TimestampUs now_us) {
  SessionEvents out;
  buttons_.poll(now_us);
  const ActionList actions = machine_.step(inputs(), now_us);
  strokes_.begin_step(actions, machine_.radius_m());
  for (const Action& a : actions.items()) apply_action(a, out);
  mover_.follow();
  strokes_.end_step();
  return out;
}

InteractionInputs SculptSession::inputs() const {
  InteractionInputs in;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    in.hands[h].pose_valid = poses_.valid(h);
    in.hands[h].position_m = glm::vec3(poses_.hand_in_world(h).origin);
    in.hands[h].buttons = buttons_.hand(h);
  }
  return in;
}

void SculptSession::apply_action(const Action& a, SessionEvents& out) {
  switch (a.kind) {
    case ActionKind::grab_begin:
    case ActionKind::freeze:
    case ActionKind::commit:
    case ActionKind::cancel:
      strokes_.apply(a, out);
      return;
    case ActionKind::move_begin:
      mover_.begin(a.hand);
      out.push({SessionEventKind::move_begin, a.hand, Reason::none, ok_status(), 0});
      return;
    case ActionKind::move_commit:
      commit_move(a, out);
      return;
    case ActionKind::move_cancel:
      if (mover_.cancel()) {
        out.push({SessionEventKind::move_cancelled, a.hand, a.reason, ok_status(), 0});
      }
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

void SculptSession::commit_move(const Action& a, SessionEvents& out) {
  const Result<ObjectMove> move = mover_.commit();
  if (!move.ok()) return;  // no move open
  const CommitOutcome done = history_.commit_move(a.hand, move->before, move->after);
  const auto kind =
      done.status.ok() ? SessionEventKind::move_committed : SessionEventKind::not_saved;
  out.push({kind, a.hand, Reason::released, done.status, done.sequence});
}

SessionEvents SculptSession::cancel_open() {
  SessionEvents out;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((strokes_.hand_mask() & (1u << h)) != 0) {
      strokes_.apply({ActionKind::cancel, h, Reason::none, 0.0f}, out);
    }
  }
  const std::uint8_t mover = mover_.hand();
  if (mover_.cancel()) {
    out.push({SessionEventKind::move_cancelled, mover, Reason::none, ok_status(), 0});
  }
  return out;
}

Status SculptSession::undo() { return step_history(journal::RecordType::undo); }

Status SculptSession::redo() { return step_history(journal::RecordType::redo); }

Status SculptSession::step_history(journal::RecordType type) {
  if (busy()) return StatusCode::failed_precondition;
  const Status s = history_.commit_history_step(type);
  // io_error means the step happened and only its record is not durable.
  if (s.ok() || s.code() == StatusCode::io_error) replay_.break_chain();
  return s;
}

Status SculptSession::apply_record(const journal::JournalRecord& record) {
  if (busy()) return StatusCode::failed_precondition;
  return replay_.apply(record);
}

Result<std::size_t> SculptSession::replay(journal::JournalReader& reader) {
  std::size_t applied = 0;
  for (;;) {
    auto record = reader.next();
    if (record.status().code() == StatusCode::unavailable ||
        record.status().code() == StatusCode::data_loss) {
      return applied;  // clean end, or a tail the caller reports and truncates
    }
    if (!record.ok()) return record.status();
    TWISTER_TRY(apply_record(*record));
    ++applied;
  }
}

}  // namespace twister::input
