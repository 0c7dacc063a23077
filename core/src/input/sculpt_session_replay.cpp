// SculptSession, history side: undo/redo and journal replay. Replay runs the same
// commit code as a live stroke so that a replayed mesh is bit-identical.
#include <bit>

#include "twister/input/sculpt_session.hpp"

namespace twister::input {
namespace {

math::Frame from_journal(const journal::JournalPose& p) {
  return math::frame_from_uv(p.origin_m, p.u, p.v);
}

}  // namespace

Status SculptSession::undo() { return step_history(journal::RecordType::undo); }

Status SculptSession::redo() { return step_history(journal::RecordType::redo); }

Status SculptSession::step_history(journal::RecordType type) {
  if (busy()) return StatusCode::failed_precondition;
  TWISTER_TRY_ASSIGN(const UndoStep step, type == journal::RecordType::undo ? history_.undo(mesh_)
                                                                            : history_.redo(mesh_));
  if (step.object_move) poses_.set_object(step.object_pose);
  journal::JournalRecord r;
  r.type = type;
  journal_append(r, nullptr);
  replay_chain_open_ = false;
  return journal_ == nullptr || journal_->healthy() ? ok_status() : Status(StatusCode::io_error);
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

Status SculptSession::apply_record(const journal::JournalRecord& record) {
  if (busy()) return StatusCode::failed_precondition;
  switch (record.type) {
    case journal::RecordType::stroke: {
      const journal::StrokeRecord& s = record.stroke;
      std::array<math::Frame, 2> start{};
      std::array<math::Frame, 2> end{};
      std::size_t n = 0;
      for (std::uint8_t h = 0; h < kHandCount; ++h) {
        if ((s.hand_mask & (1u << h)) == 0) continue;
        start[n] = from_journal(s.start[h]);
        end[n] = from_journal(s.end[h]);
        ++n;
      }
      if (s.chain_step == 0) {
        TWISTER_TRY(plan_.build(rest(), std::span(start).first(n), s.radius_m,
                                static_cast<math::WarpMethod>(s.method)));
      } else {
        // A freeze step reuses the weights of its chain: the chain must be the one
        // just replayed, with the same hands, radius and method.
        if (!replay_chain_open_ || s.chain_step != replay_chain_step_ + 1 ||
            plan_.hand_count() != n || plan_.radius() != s.radius_m ||
            static_cast<std::uint8_t>(plan_.method()) != s.method) {
          return StatusCode::data_loss;
        }
        TWISTER_TRY(plan_.rebase(std::span(start).first(n)));
      }
      TWISTER_TRY(plan_.update(std::span(end).first(n)));
      TWISTER_TRY(commit_plan(record, false, nullptr));
      replay_chain_open_ = true;
      replay_chain_step_ = s.chain_step;
      ++replay_stats_.strokes;
      break;
    }
    case journal::RecordType::object_move: {
      const math::Frame after = from_journal(record.move.object_after);
      if (!math::is_orthonormal(after)) return StatusCode::data_loss;
      history_.begin_entry();
      history_.record_object(poses_.object(), after);
      history_.end_entry().ignore();
      poses_.set_object(after);
      ++replay_stats_.moves;
      break;
    }
    case journal::RecordType::undo:
    case journal::RecordType::redo: {
      const bool is_undo = record.type == journal::RecordType::undo;
      auto step = is_undo ? history_.undo(mesh_) : history_.redo(mesh_);
      if (!step.ok()) return StatusCode::data_loss;
      if (step->object_move) poses_.set_object(step->object_pose);
      replay_chain_open_ = false;
      ++(is_undo ? replay_stats_.undos : replay_stats_.redos);
      break;
    }
  }
  next_sequence_ = record.sequence + 1;
  return ok_status();
}

}  // namespace twister::input
