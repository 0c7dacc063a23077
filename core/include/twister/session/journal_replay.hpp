// JournalReplay: applies journal records to a session's model (at start-up, in
// `twister replay`, in tests) through the same commit code as a live session
// (SessionHistory's apply_* functions), so the same initial mesh gives a
// bit-identical mesh and object pose. Records keep their sequence numbers.
//
// A stroke record rebuilds the plan from its start poses (chain step 0) or rebases
// the plan the previous record left (a freeze step: same hands, radius and method,
// the next chain step), then updates it to the end poses (each hand's screw the long
// way round where the record's long_turns says so) and commits. A refined record
// with chain step > 0 is the refined end of its clutch chain: refined under the
// chain's combined warp (failed_precondition when the replaying session has no
// refinement memory or did not see the chain from its step 0).
// The plan is shared with the session's StrokeController: records are applied only
// while no stroke is open (the session checks). No allocation; not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/session_history.hpp"
#include "twister/session/session_poses.hpp"

namespace twister::session {

struct ReplayStats {
  std::size_t strokes = 0;
  std::size_t moves = 0;
  std::size_t undos = 0;
  std::size_t redos = 0;
};

class JournalReplay {
 public:
  // Every reference must outlive this object.
  JournalReplay(math::WarpPlan& plan, const LiveMesh& mesh, SessionHistory& history,
                SessionPoses& poses);
  JournalReplay(const JournalReplay&) = delete;
  JournalReplay& operator=(const JournalReplay&) = delete;

  // Applies one record. data_loss: the record does not fit the model's state (a
  // freeze step without its chain, undo with an empty history, an object pose that
  // is not orthonormal); invalid_argument / resource_exhausted / failed_precondition:
  // the warp plan refused the record. On error nothing was applied.
  Status apply(const journal::JournalRecord& record);

  // An undo or redo happened outside the replay: a freeze step can no longer
  // continue the chain replayed before it.
  void break_chain() { chain_open_ = false; }

  const ReplayStats& stats() const { return stats_; }

 private:
  Status apply_stroke(const journal::StrokeRecord& stroke);
  Status apply_move(const journal::ObjectMoveRecord& move);
  Status apply_history_step(journal::RecordType type);

  math::WarpPlan& plan_;
  const LiveMesh& mesh_;
  SessionHistory& history_;
  SessionPoses& poses_;
  bool chain_open_ = false;  // the plan holds the chain of the last stroke record
  std::uint16_t chain_step_ = 0;
  ReplayStats stats_{};
};

}  // namespace twister::session
