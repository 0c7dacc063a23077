#include "twister/session/journal_replay.hpp"

#include <array>
#include <span>

#include "twister/input/button_map.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::session {

JournalReplay::JournalReplay(math::WarpPlan& plan, const LiveMesh& mesh, SessionHistory& history,
                             SessionPoses& poses)
    : plan_(plan), mesh_(mesh), history_(history), poses_(poses) {}

Status JournalReplay::apply(const journal::JournalRecord& record) {
  switch (record.type) {
    case journal::RecordType::stroke:
      TWISTER_TRY(apply_stroke(record.stroke));
      break;
    case journal::RecordType::object_move:
      TWISTER_TRY(apply_move(record.move));
      break;
    case journal::RecordType::undo:
    case journal::RecordType::redo:
      TWISTER_TRY(apply_history_step(record.type));
      break;
  }
  history_.resume_after(record.sequence);
  return ok_status();
}

Status JournalReplay::apply_stroke(const journal::StrokeRecord& s) {
  math::PlanFrames start;
  math::PlanFrames end;
  std::uint8_t long_turns = 0;  // by plan hand, as WarpPlan::update_turns wants it
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((s.hand_mask & (1u << h)) == 0) continue;
    if ((s.long_turns & (1u << h)) != 0)
      long_turns = static_cast<std::uint8_t>(long_turns | (1u << start.size()));
    // One per hand: cannot be full.
    start.push_back(s.start[h]).ignore();
    end.push_back(s.end[h]).ignore();
  }
  const std::size_t n = start.size();
  // A refined chain step ends its chain (CommitRefinement): it must continue the
  // chain replayed here (checked below) and be one the station can compose: not scodef.
  if (s.refine_threshold_m > 0.0 && s.chain_step != 0 &&
      static_cast<math::WarpMethod>(s.method) == math::WarpMethod::scodef) {
    return StatusCode::data_loss;
  }
  // The record's group (version 5; none before): decode_payload checked it.
  const math::SymmetrySpec symmetry{static_cast<math::SymmetryKind>(s.symmetry.kind),
                                    s.symmetry.mirrors, s.symmetry.axis, s.symmetry.order};
  if (s.chain_step == 0) {
    math::SymmetryGroup group;
    if (!group.set(symmetry).ok()) return StatusCode::data_loss;
    TWISTER_TRY(plan_.build(mesh_.rest(), start, s.radius_m,
                            static_cast<math::WarpMethod>(s.method), group));
  } else {
    // A freeze step reuses the weights of its chain: the chain must be the one just
    // replayed, with the same hands, radius, method and symmetry.
    if (!chain_open_ || s.chain_step != chain_step_ + 1 || plan_.hand_count() != n ||
        plan_.radius() != s.radius_m || static_cast<std::uint8_t>(plan_.method()) != s.method ||
        plan_.symmetry() != symmetry) {
      return StatusCode::data_loss;
    }
    TWISTER_TRY(plan_.rebase(start));
  }
  // The screws from the poses alone (and the turn sense the record gives): the same
  // numbers the live stroke computed, minimal or unwrapped.
  TWISTER_TRY(plan_.update_turns(end, long_turns));
  TWISTER_TRY(history_.apply_stroke(plan_, s.refine_threshold_m, s.refine_local, s.chain_step));
  chain_open_ = s.refine_threshold_m == 0.0;  // a refined commit ended its chain
  chain_step_ = s.chain_step;
  ++stats_.strokes;
  return ok_status();
}

Status JournalReplay::apply_move(const journal::ObjectMoveRecord& move) {
  const math::Frame after = move.object_after;
  if (!math::is_orthonormal(after)) return StatusCode::data_loss;
  history_.apply_move(poses_.object(), after);
  poses_.set_object(after);
  ++stats_.moves;
  return ok_status();
}

Status JournalReplay::apply_history_step(journal::RecordType type) {
  if (!history_.apply_history_step(type).ok()) return StatusCode::data_loss;
  chain_open_ = false;
  ++(type == journal::RecordType::undo ? stats_.undos : stats_.redos);
  return ok_status();
}

}  // namespace twister::session
