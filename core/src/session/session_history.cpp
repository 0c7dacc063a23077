#include "twister/session/session_history.hpp"

#include <glm/vec3.hpp>

#include "twister/base/assert.hpp"

namespace twister::session {

namespace {

void report_refinement(const RefineReport& refined, std::uint32_t sequence, SessionEvents& out) {
  if (!refined.ran) return;
  out.push(make_event(SessionEventKind::refined, 0,
                      payload::Refinement{sequence, refined.result.edges_split}));
  if (refined.result.stop != mesh::RefineStop::done) {
    out.push(make_event(SessionEventKind::refine_stopped, 0,
                        payload::RefinementStop{sequence, refined.result.stop},
                        StatusCode::resource_exhausted));
  }
}

}  // namespace

SessionHistory::SessionHistory(LiveMesh& mesh, SessionPoses& poses, std::span<VertexChange> changes,
                               std::span<UndoEntry> entries, journal::JournalWriter* journal,
                               std::span<TriangleChange> triangle_changes)
    : mesh_(mesh), poses_(poses), history_(changes, entries, triangle_changes), journal_(journal) {}

CommitOutcome SessionHistory::do_commit(const math::WarpPlan& plan,
                                        const journal::StrokeRecord& stroke, SessionEvents& out,
                                        bool plan_goes_on) {
  const std::uint32_t sequence = next_sequence_;
  const double threshold =
      refinement_ != nullptr ? refinement_->threshold_for(plan, stroke, plan_goes_on) : 0.0;
  // The warp into the live columns first (it may fail: nothing is written), then the
  // record, then the mesh: a stroke whose record is not durable never reaches it.
  if (const Status s = plan.apply(mesh_.rest(), mesh_.live()); !s.ok()) return {s, sequence};
  journal::JournalRecord r;
  r.type = journal::RecordType::stroke;
  r.stroke = stroke;
  r.stroke.refine_threshold_m = threshold;
  r.stroke.refine_local = threshold > 0.0 && refinement_->local();
  if (const Status saved = append(r); !saved.ok()) return {saved, sequence};
  // A chain's start is kept only when its end may refine: it does not change the mesh.
  const bool keep = plan_goes_on && refinement_ != nullptr && refinement_->live_threshold() > 0.0;
  commit_live(plan, {threshold, r.stroke.refine_local, stroke.chain_step, keep}, sequence, &out);
  if (!plan_goes_on && stroke.chain_step != 0 && threshold == 0.0 && refinement_ != nullptr &&
      refinement_->live_threshold() > 0.0) {
    refinement_->chain_ended_unrefined();
  }
  return {ok_status(), sequence};
}

CommitOutcome SessionHistory::commit_move(std::uint8_t hand, const math::Frame& before,
                                          const math::Frame& after) {
  journal::JournalRecord r;
  r.type = journal::RecordType::object_move;
  r.move.hand = hand;
  r.move.object_before = journal::as_stored(before);
  r.move.object_after = journal::as_stored(after);
  const std::uint32_t sequence = next_sequence_;
  if (const Status saved = append(r); !saved.ok()) {
    poses_.set_object(before);  // the last durable pose
    return {saved, sequence};
  }
  apply_move(before, after);
  return {ok_status(), sequence};
}

Status SessionHistory::commit_history_step(journal::RecordType type) {
  TWISTER_TRY(apply_history_step(type));
  journal::JournalRecord r;
  r.type = type;
  const Status saved = append(r);
  if (saved.ok()) return saved;
  // Not durable: take the step back (undo and redo restore bit-identically).
  const auto back =
      type == journal::RecordType::undo ? journal::RecordType::redo : journal::RecordType::undo;
  const Status undone = apply_history_step(back);
  TWISTER_ASSERT(undone.ok());
  return saved;
}

Status SessionHistory::apply_stroke(const math::WarpPlan& plan, double refine_threshold_m,
                                    bool refine_local, std::uint16_t chain_step) {
  return apply_plan(plan, refine_threshold_m, refine_local, chain_step, nullptr);
}

void SessionHistory::apply_move(const math::Frame& before, const math::Frame& after) {
  history_.begin_entry();
  history_.record_object(before, after);
  history_.end_entry().ignore();  // an object-only entry always fits
}

Status SessionHistory::apply_history_step(journal::RecordType type) {
  TWISTER_ASSERT(type == journal::RecordType::undo || type == journal::RecordType::redo);
  mesh::Mesh& mesh = mesh_.mesh();
  TWISTER_TRY_ASSIGN(const UndoStep step,
                     type == journal::RecordType::undo ? history_.undo(mesh) : history_.redo(mesh));
  if (refinement_ != nullptr) refinement_->forget_chain();
  if (step.object_move) poses_.set_object(step.object_pose);
  return ok_status();
}

Status SessionHistory::apply_plan(const math::WarpPlan& plan, double refine_threshold_m,
                                  bool refine_local, std::uint16_t chain_step, SessionEvents* out) {
  if (refine_threshold_m > 0.0 && (refinement_ == nullptr || !refinement_->available())) {
    return StatusCode::failed_precondition;
  }
  // A refined chain end needs the chain this session saw from its step 0.
  if (refine_threshold_m > 0.0 && chain_step != 0 &&
      !refinement_->chain_refinable(plan, chain_step)) {
    return StatusCode::failed_precondition;
  }
  TWISTER_TRY(plan.apply(mesh_.rest(), mesh_.live()));
  // Replay cannot know whether a chain follows an unrefined step 0: it keeps its start.
  const bool keep = refinement_ != nullptr && refinement_->available() && refine_threshold_m == 0.0;
  commit_live(plan, {refine_threshold_m, refine_local, chain_step, keep}, next_sequence_, out);
  return ok_status();
}

void SessionHistory::commit_live(const math::WarpPlan& plan, const CommitShape& shape,
                                 std::uint32_t sequence, SessionEvents* out) {
  const math::VertexColumns live = mesh_.live();
  mesh::Mesh& mesh = mesh_.mesh();
  history_.begin_entry();
  bool undoable = true;
  RefineReport refined{};
  const bool chain_end = shape.refine_threshold_m > 0.0 && shape.chain_step != 0;
  if (refinement_ != nullptr) {
    refinement_->note_commit(plan, shape.chain_step, shape.keep_chain);
    // Refinement first: it needs the rest positions. A chain's end puts its vertices
    // back at the chain's start, so their undo changes (from where the last step left
    // them) are recorded before.
    if (chain_end) {
      for (const std::uint32_t i : plan.indices()) {
        const glm::vec3 after{live.x[i], live.y[i], live.z[i]};
        if (!history_.record(i, mesh.position(i), after).ok()) undoable = false;
      }
      refined =
          refinement_->refine_chain(plan, shape.refine_threshold_m, history_, shape.refine_local);
    } else {
      refined = refinement_->refine(plan, shape.refine_threshold_m, history_, shape.refine_local);
    }
  }
  undoable = undoable && refined.undoable;
  const bool recorded = chain_end && refinement_ != nullptr;
  for (const std::uint32_t i : plan.indices()) {
    const glm::vec3 after{live.x[i], live.y[i], live.z[i]};
    if (!recorded && !history_.record(i, mesh.position(i), after).ok()) undoable = false;
    mesh.set_position(i, after);
  }
  if (!history_.end_entry().ok()) undoable = false;
  if (!undoable && out != nullptr) {
    out->push(make_event(SessionEventKind::history_overflow, 0, payload::RecordRef{sequence},
                         StatusCode::resource_exhausted));
  }
  if (out != nullptr) report_refinement(refined, sequence, *out);
}

Status SessionHistory::append(journal::JournalRecord& record) {
  record.sequence = next_sequence_;
  if (journal_ != nullptr) {
    // A failure that left a partial record behind is cut off before anything follows it.
    if (!journal_->healthy()) TWISTER_TRY(journal_->repair());
    TWISTER_TRY(journal_->append(record));
  }
  ++next_sequence_;
  return ok_status();
}

}  // namespace twister::session
