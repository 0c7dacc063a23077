// SessionHistory: the one place where the model changes for good. Each commit (a
// stroke's warp copied from the live columns into the mesh, an object move) becomes
// one UndoHistory entry and one journal record with the next sequence number
// (appended and synced before the call returns); undo and redo step the history and
// are journaled as well. Replay (JournalReplay) uses the apply_* functions: the same
// changes without writing records, so a replayed model is bit-identical.
//
// Write-ahead: a commit's record is appended and synced BEFORE the model changes, so
// the model never holds a change the journal does not. When the append or its sync
// fails the commit is not made: the mesh, the object pose and the undo history stay
// as after the last saved record, the sequence number is not used, and the caller
// gets io_error (a stroke's committer reports `not_saved`). A journal left broken by
// a failure (its partial record could not be cut off) is repaired before the next
// append. A commit too large for the history is applied but not undoable
// (history_overflow event).
// Refinement (CommitRefinement, optional): a stroke commit whose record carries a
// threshold refines the mesh in apply_plan, live and replayed alike (refined and,
// at a capacity, refine_stopped events); with a chain step > 0 it is the end of a
// clutch chain, refined under the chain's combined warp. Every commit tells the
// refinement its chain step (ClutchChain keeps what a chain's end needs).
// Memory: the mesh, poses, history storage and journal are the caller's and must
// outlive this object; no allocation. Not thread-safe.
#pragma once

#include <cstdint>
#include <span>

#include "twister/base/status.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/session/commit_refinement.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/session_events.hpp"
#include "twister/session/session_poses.hpp"
#include "twister/session/stroke_commit_sink.hpp"
#include "twister/session/undo_history.hpp"

namespace twister::session {

class SessionHistory final : public StrokeCommitSink {
 public:
  // `journal` may be null (no recording; sequence numbers still count).
  // `triangle_changes`: the undo pool for refined commits' topology.
  SessionHistory(LiveMesh& mesh, SessionPoses& poses, std::span<VertexChange> changes,
                 std::span<UndoEntry> entries, journal::JournalWriter* journal,
                 std::span<TriangleChange> triangle_changes = {});
  SessionHistory(const SessionHistory&) = delete;
  SessionHistory& operator=(const SessionHistory&) = delete;

  // Live, journaled. A stroke commits through StrokeCommitSink::commit().
  // A finished object move of `hand` (the object already stands at `after`): its
  // sequence, or io_error when its record could not be saved (the object is put
  // back at `before`; nothing else changed).
  CommitOutcome commit_move(std::uint8_t hand, const math::Frame& before, const math::Frame& after);
  // Undo (type undo) or redo (type redo) of the newest entry, then its record.
  // failed_precondition: nothing to undo/redo; out_of_range: the history does not fit
  // the mesh. io_error: its record could not be saved, so the step was taken back
  // (mesh, pose and history as before the call).
  Status commit_history_step(journal::RecordType type);

  // Commits refine through `refinement` (may be null: never); it must outlive this.
  void set_refinement(CommitRefinement* refinement) { refinement_ = refinement; }

  // Replay, not journaled. The warp of `plan` (updated to its end poses), refined to
  // the record's threshold (0: not refined); errors of WarpPlan::apply, or
  // failed_precondition for a threshold without refinement storage (then nothing
  // changed).
  // `refine_local`: refined over the stroke's region (a version 4 record).
  // `chain_step` > 0 with a threshold: the refined end of a clutch chain, which needs
  // the chain's earlier steps applied here (failed_precondition otherwise, nothing
  // changed).
  Status apply_stroke(const math::WarpPlan& plan, double refine_threshold_m = 0.0,
                      bool refine_local = false, std::uint16_t chain_step = 0);
  // An undo entry for an object move (the caller sets the pose).
  void apply_move(const math::Frame& before, const math::Frame& after);
  // Undo or redo without a record; errors as commit_history_step.
  Status apply_history_step(journal::RecordType type);
  // The record `sequence` was applied: the next record gets sequence + 1.
  void resume_after(std::uint32_t sequence) { next_sequence_ = sequence + 1; }
  // A new journal (exhibit rotation): records are numbered from 0 again.
  void restart_sequence() { next_sequence_ = 0; }

  std::uint32_t next_sequence() const { return next_sequence_; }
  const UndoHistory& undo_history() const { return history_; }
  // The history, to restore a checkpoint into (SessionCheckpoint only).
  UndoHistory& restorable() { return history_; }

 private:
  CommitOutcome do_commit(const math::WarpPlan& plan, const journal::StrokeRecord& stroke,
                          SessionEvents& out, bool plan_goes_on) override;
  // The commit of a warp, live and replayed alike: the plan applied to the live
  // columns, then commit_live().
  Status apply_plan(const math::WarpPlan& plan, double refine_threshold_m, bool refine_local,
                    std::uint16_t chain_step, SessionEvents* out);
  // The record's shape for the commit: threshold, local, chain step, and whether a
  // step-0 commit keeps the chain's start (the plan may go on).
  struct CommitShape {
    double refine_threshold_m = 0.0;
    bool refine_local = false;
    std::uint16_t chain_step = 0;
    bool keep_chain = false;
  };
  // The mesh refined at rest (when the threshold is > 0; a chain's end under the
  // chain's warp), the live columns of the plan's vertices into the mesh, one undo
  // entry (a history_overflow event with `sequence` when it is too large to undo;
  // refined / refine_stopped events).
  void commit_live(const math::WarpPlan& plan, const CommitShape& shape, std::uint32_t sequence,
                   SessionEvents* out);
  // Gives `record` the next sequence and appends and syncs it (when journaling); the
  // sequence advances only when it is durable. io_error: not saved.
  Status append(journal::JournalRecord& record);

  LiveMesh& mesh_;
  SessionPoses& poses_;
  UndoHistory history_;
  journal::JournalWriter* journal_;
  CommitRefinement* refinement_ = nullptr;
  std::uint32_t next_sequence_ = 0;
};

}  // namespace twister::session
