// SculptSession: the wiring. Each step: buttons -> machine -> actions dispatched to
// the part that owns them (strokes, object move, plain events), then the open move
// and stroke follow the hands, then the step's commands run (undo/redo through the
// history, the method through the strokes). History and replay calls pass straight
// through.
#include "twister/session/sculpt_session.hpp"

#include <glm/vec3.hpp>

namespace twister::session {
namespace {

SessionCommandKind command_for(input::ButtonRole role) {
  switch (role) {
    case input::ButtonRole::redo:
      return SessionCommandKind::redo;
    case input::ButtonRole::method_cycle:
      return SessionCommandKind::next_method;
    case input::ButtonRole::symmetry_cycle:
      return SessionCommandKind::cycle_symmetry;
    default:
      return SessionCommandKind::undo;
  }
}

math::WarpMethod next_method(math::WarpMethod m) {
  switch (m) {
    case math::WarpMethod::twister:
      return math::WarpMethod::rottran;
    case math::WarpMethod::rottran:
      return math::WarpMethod::scodef;
    case math::WarpMethod::scodef:
      return math::WarpMethod::twister;
  }
  return math::WarpMethod::twister;
}

}  // namespace

const char* session_command_name(SessionCommandKind kind) {
  switch (kind) {
    case SessionCommandKind::undo:
      return "undo";
    case SessionCommandKind::redo:
      return "redo";
    case SessionCommandKind::next_method:
      return "next_method";
    case SessionCommandKind::set_method:
      return "set_method";
    case SessionCommandKind::cycle_symmetry:
      return "cycle_symmetry";
    case SessionCommandKind::new_sculpture:
      return "new_sculpture";
    case SessionCommandKind::undo_new_sculpture:
      return "undo_new_sculpture";
  }
  return "unknown";
}

SculptSession::SculptSession(const SculptSessionConfig& config, mesh::Mesh& mesh,
                             SculptStorage storage, journal::JournalWriter* journal)
    : mesh_(mesh, storage.live_x, storage.live_y, storage.live_z),
      refinement_(mesh_, storage.refine, config.refine, storage.chain_start),
      buttons_(config.debounce, config.buttons),
      machine_(config.interaction),
      plan_(storage.plan),
      history_(mesh_, poses_, storage.undo_changes, storage.undo_entries, journal,
               storage.undo_triangle_changes),
      strokes_(plan_, mesh_, poses_, history_, config.method, config.turns),
      mover_(poses_),
      replay_(plan_, mesh_, history_, poses_),
      normals_(storage.normals),
      symmetry_cycle_(config.symmetry_cycle.resolved(config.symmetry)) {
  history_.set_refinement(&refinement_);
  // An invalid group (the configuration checks it) leaves strokes unsymmetrised.
  strokes_.set_symmetry(config.symmetry).ignore();
  const std::size_t capacity = mesh.vertex_capacity();
  if (normals_.x.size() < capacity || normals_.y.size() < capacity ||
      normals_.z.size() < capacity) {
    normals_ = {};  // too small for the mesh: no normals rather than stale ones
  }
  normals_sequence_ = history_.next_sequence() + 1;  // forces the first computation
  refresh_normals();
}

void SculptSession::refresh_normals() {
  if (normals_.x.empty() || normals_sequence_ == history_.next_sequence()) return;
  compute_vertex_normals(mesh_.mesh(), normals_).ignore();  // sized for the capacity
  normals_sequence_ = history_.next_sequence();
}

void SculptSession::checkpoint_restored() {
  refinement_.forget_chain();  // checkpoints hold no chain (taken between strokes)
  normals_sequence_ = history_.next_sequence() + 1;  // whatever they were computed for
  refresh_normals();
}

Status SculptSession::reset_model(const mesh::Mesh& base) {
  if (busy()) return StatusCode::failed_precondition;
  TWISTER_TRY(mesh_.mesh().copy_from(base));
  history_.restorable().clear();
  history_.restart_sequence();
  poses_.set_object(math::Frame{});  // as constructed
  checkpoint_restored();             // no chain, normals of the new model
  return ok_status();
}

mesh::NormalColumns SculptSession::normals() const {
  if (normals_.x.empty()) return {};
  const std::size_t n = mesh_.mesh().vertex_count();
  return {normals_.x.first(n), normals_.y.first(n), normals_.z.first(n)};
}

Status SculptSession::feed_button(const ports::ButtonEdge& edge) { return buttons_.feed(edge); }

Status SculptSession::set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world) {
  return poses_.set_hand(hand, valid, pose_in_world);
}

SessionEvents SculptSession::step(ports::TimestampUs now_us) {
  SessionEvents out;
  buttons_.poll(now_us);
  const input::ActionList actions = machine_.step(inputs(), now_us);
  strokes_.begin_step(actions, machine_.radius_m());
  for (const input::Action& a : actions.items()) apply_action(a, out);
  mover_.follow();
  strokes_.end_step(out);
  for (const input::ButtonCommand& c : buttons_.commands()) {
    run_command({command_for(c.role), c.hand, math::WarpMethod::twister}, out);
  }
  for (std::size_t i = 0; i < queued_.size(); ++i) run_command(queued_[i], out);
  queued_.clear();
  refresh_normals();
  return out;
}

Status SculptSession::submit(const SessionCommand& command) {
  if (command.hand >= input::kHandCount) return StatusCode::invalid_argument;
  return queued_.push_back(command);  // resource_exhausted: kMaxQueuedCommands queued
}

input::InteractionInputs SculptSession::inputs() const {
  input::InteractionInputs in;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    in.hands[h].pose_valid = poses_.valid(h);
    in.hands[h].position_m = glm::vec3(poses_.hand_in_world(h).origin);
    in.hands[h].buttons = buttons_.hand(h);
    in.hands[h].buttons_valid = buttons_.connected();
  }
  return in;
}

void SculptSession::apply_action(const input::Action& a, SessionEvents& out) {
  switch (a.kind) {
    case input::ActionKind::grab_begin:
    case input::ActionKind::freeze:
    case input::ActionKind::unfreeze:
    case input::ActionKind::commit:
    case input::ActionKind::cancel:
      strokes_.apply(a, out);
      return;
    case input::ActionKind::move_begin:
      mover_.begin(a.hand);
      out.push(make_event(SessionEventKind::move_begin, a.hand));
      return;
    case input::ActionKind::move_commit:
      commit_move(a, out);
      return;
    case input::ActionKind::move_cancel:
      if (mover_.cancel()) {
        out.push(make_event(SessionEventKind::move_cancelled, a.hand, payload::Reasoned{a.reason}));
      }
      return;
    case input::ActionKind::radius_begin:
      return;
    // The machine's other outputs are reported as they are: each becomes its event
    // here, once.
    case input::ActionKind::radius_change:
      out.push(make_event(SessionEventKind::radius_changed, a.hand,
                          payload::Radius{static_cast<double>(a.radius_m)}));
      return;
    case input::ActionKind::radius_end:
      out.push(make_event(SessionEventKind::radius_set, a.hand,
                          payload::Radius{static_cast<double>(a.radius_m)}));
      return;
    case input::ActionKind::tracking_lost:
      out.push(make_event(SessionEventKind::tracking_lost, a.hand));
      return;
    case input::ActionKind::tracking_resumed:
      out.push(make_event(SessionEventKind::tracking_resumed, a.hand));
      return;
    case input::ActionKind::refused:
      out.push(make_event(SessionEventKind::refused, a.hand, payload::Reasoned{a.reason}));
      return;
  }
}

void SculptSession::commit_move(const input::Action& a, SessionEvents& out) {
  const Result<ObjectMove> move = mover_.commit();
  if (!move.ok()) return;  // no move open
  const CommitOutcome done = history_.commit_move(a.hand, move->before, move->after);
  if (done.status.ok()) {
    out.push(
        make_event(SessionEventKind::move_committed, a.hand, payload::RecordRef{done.sequence}));
  } else {
    out.push(make_event(SessionEventKind::not_saved, a.hand,
                        payload::StrokeEnd{input::Reason::released, done.sequence}, done.status));
  }
}

SessionEvents SculptSession::cancel_open() {
  SessionEvents out;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((strokes_.hand_mask() & (1u << h)) != 0) {
      strokes_.apply({input::ActionKind::cancel, h, input::Reason::stopped, 0.0f}, out);
    }
  }
  const std::uint8_t mover = mover_.hand();
  if (mover_.cancel()) {
    out.push(make_event(SessionEventKind::move_cancelled, mover,
                        payload::Reasoned{input::Reason::stopped}));
  }
  return out;
}

void SculptSession::run_command(const SessionCommand& c, SessionEvents& out) {
  const auto refuse = [&](input::Reason reason, Status status) {
    out.push(make_event(SessionEventKind::command_refused, c.hand,
                        payload::CommandRefusal{c.kind, reason}, status));
  };
  switch (c.kind) {
    case SessionCommandKind::undo:
    case SessionCommandKind::redo:
      run_history_command(c, out);
      return;
    case SessionCommandKind::next_method:
    case SessionCommandKind::set_method: {
      // The open stroke keeps its method (its weights and journal record use it).
      if (strokes_.active())
        return refuse(input::Reason::busy, Status(StatusCode::failed_precondition));
      const math::WarpMethod m =
          c.kind == SessionCommandKind::set_method ? c.method : next_method(strokes_.method());
      strokes_.set_method(m);
      out.push(make_event(SessionEventKind::method_changed, c.hand, payload::Method{m}));
      return;
    }
    case SessionCommandKind::cycle_symmetry:
      run_symmetry_command(c, out);
      return;
    case SessionCommandKind::new_sculpture:
    case SessionCommandKind::undo_new_sculpture:
      // Vocabulary of protocol 7; the station acts on them where the feature is on.
      return refuse(input::Reason::not_available, Status(StatusCode::failed_precondition));
  }
}

void SculptSession::run_history_command(const SessionCommand& c, SessionEvents& out) {
  const bool undo = c.kind == SessionCommandKind::undo;
  const std::uint32_t sequence = history_.next_sequence();
  const Status s = step_history(undo ? journal::RecordType::undo : journal::RecordType::redo);
  if (s.ok()) {
    out.push(make_event(undo ? SessionEventKind::undone : SessionEventKind::redone, c.hand,
                        payload::RecordRef{sequence}));
    return;
  }
  // io_error: its record could not be saved, so the step was taken back (reason none);
  // out_of_range: the history does not fit the mesh.
  input::Reason reason = input::Reason::none;
  if (busy()) {
    reason = input::Reason::busy;
  } else if (s.code() == StatusCode::failed_precondition) {
    reason = undo ? input::Reason::nothing_to_undo : input::Reason::nothing_to_redo;
  }
  out.push(make_event(SessionEventKind::command_refused, c.hand,
                      payload::CommandRefusal{c.kind, reason}, s));
}

void SculptSession::run_symmetry_command(const SessionCommand& c, SessionEvents& out) {
  // The open stroke keeps its group (its weights and journal record use it).
  input::Reason reason = input::Reason::busy;
  Status status(StatusCode::failed_precondition);
  if (!strokes_.active()) {
    const Result<math::SymmetrySpec> next = symmetry_cycle_.next(strokes_.symmetry());
    status = next.ok() ? strokes_.set_symmetry(*next) : next.status();
    if (status.ok()) {
      out.push(make_event(SessionEventKind::symmetry_changed, c.hand, payload::Symmetry{*next}));
      return;
    }
    reason = input::Reason::not_available;  // one group only: nothing to cycle to
  }
  out.push(make_event(SessionEventKind::command_refused, c.hand,
                      payload::CommandRefusal{c.kind, reason}, status));
}

Status SculptSession::undo() { return step_history(journal::RecordType::undo); }

Status SculptSession::redo() { return step_history(journal::RecordType::redo); }

Status SculptSession::step_history(journal::RecordType type) {
  if (busy()) return StatusCode::failed_precondition;
  const Status s = history_.commit_history_step(type);
  // io_error: not saved (the step was taken back); the chain is broken all the same.
  if (s.ok() || s.code() == StatusCode::io_error) replay_.break_chain();
  refresh_normals();
  return s;
}

SessionState SculptSession::state() const {
  SessionState st;
  st.radius_m = machine_.radius_m();
  st.radius_gesture_enabled = machine_.config().radius_gesture;
  st.radius_gesture_active = machine_.radius_active();
  st.method = strokes_.method();
  st.turn_tracking = strokes_.drive(0).config().tracking;
  st.stroke_active = strokes_.active();
  st.stroke_method = strokes_.active() ? plan_.method() : strokes_.method();
  st.symmetry.next = strokes_.symmetry();
  st.symmetry.stroke = strokes_.active() ? plan_.symmetry() : strokes_.symmetry();
  st.chain_step = strokes_.chain_step();
  st.moving_object = mover_.moving();
  st.undo_depth = history_.undo_history().undo_depth();
  st.redo_depth = history_.undo_history().redo_depth();
  st.next_sequence = history_.next_sequence();
  st.refine = refinement_.status();
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    HandView& v = st.hands[h];
    const HandDrive& drive = strokes_.drive(h);
    v.state = machine_.state(h);
    v.buttons = buttons_.hand(h);
    v.tracked = poses_.valid(h);
    v.in_stroke = (strokes_.hand_mask() & (1u << h)) != 0;
    v.engaged = !v.in_stroke || drive.engaged();
    v.turn_rad = v.in_stroke ? drive.turned_rad() : 0.0;
    v.turn_limit_rad = drive.limit_rad();
    v.at_turn_limit = v.in_stroke && drive.at_limit();
  }
  return st;
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
      refresh_normals();
      return applied;  // clean end, or a tail the caller reports and truncates
    }
    if (!record.ok()) return record.status();
    TWISTER_TRY(apply_record(*record));
    ++applied;
  }
}

}  // namespace twister::session
