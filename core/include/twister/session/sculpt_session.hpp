// SculptSession: the sculpting session of one station. It consumes hand poses
// (world frame, valid or lost), raw button edges and time; debounces the buttons,
// runs the InteractionMachine and turns its actions into warps of the mesh
// (math::WarpPlan), rigid object moves, undo/redo entries and journal records.
//
// Frames: hand poses come in the world (tracker) frame. The mesh lives in the
// object frame; object_pose() places it in the world (a rigid move changes only
// the pose). Warps are computed on hand poses expressed in the object frame, and
// the journal records exactly those poses, so replay is bit-identical.
//
// Strokes: a stroke segment is a period in which the set of grabbing hands is
// constant. Release commits it; freeze (the clutch) commits it and rebases the plan
// (same vertices and weights, chain_step + 1) with the hand disengaged until freeze
// is released; a hand joining or leaving commits the segment and starts a new one for
// the hands that still grab. A cancel (tracking lost too long) drops the open segment:
// the model stays as at its start. One stroke may turn past a half turn, up to the
// turn limit (SculptSessionConfig::turns, docs/unwrap.md).
// Each commit is one journal record and one undo entry; the record is appended and
// synced before the model changes, and a commit whose record cannot be saved is not
// made (not_saved; at a freeze press or release the stroke ends there). With
// refinement on (SculptSessionConfig::refine), a commit that ends its stroke refines
// the mesh into its spare capacity (CommitRefinement, docs/refinement.md); a clutch
// chain is refined at the commit that ends it, under the chain's combined warp.
// Commands (undo, redo, warp method) come from buttons (ButtonMap roles and chords)
// or submit() and run at the end of a step; state() is the display's snapshot.
//
// Structure (docs/interaction.md "SculptSession's parts"): a thin composition of
// ButtonFrontEnd (debounce + map), SessionPoses (hands, object pose),
// InteractionMachine, StrokeController (segments, WarpPlan lifecycle), ObjectMover,
// SessionHistory (mesh commits, undo, journal) and JournalReplay, over a LiveMesh
// (the mesh and the live stroke's warped columns).
//
// Memory: everything comes from SculptStorage given at construction (see
// SculptSessionWithStorage); no heap allocation ever. Not thread-safe: call from
// the station's poll loop only. Time in microseconds on a monotonic clock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/base/result.hpp"
#include "twister/input/button_debouncer.hpp"
#include "twister/input/button_front_end.hpp"
#include "twister/input/button_map.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/mesh/vertex_normals.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/commit_refinement.hpp"
#include "twister/session/hand_drive.hpp"
#include "twister/session/journal_replay.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/object_mover.hpp"
#include "twister/session/session_command.hpp"
#include "twister/session/session_events.hpp"
#include "twister/session/session_history.hpp"
#include "twister/session/session_poses.hpp"
#include "twister/session/session_state.hpp"
#include "twister/session/stroke_controller.hpp"
#include "twister/session/symmetry_cycle.hpp"
#include "twister/session/undo_history.hpp"

namespace twister::session {

// History size the station uses unless configured otherwise. A replay tool must use
// the same sizes to reproduce undo records exactly once the history has overflowed.
inline constexpr std::size_t kDefaultUndoChanges = std::size_t{1} << 18;
inline constexpr std::size_t kDefaultUndoEntries = 64;
// Triangle changes of refined commits (about four per vertex a refinement adds).
inline constexpr std::size_t kDefaultUndoTriangleChanges = std::size_t{1} << 18;

struct SculptSessionConfig {
  input::InteractionConfig interaction{};
  input::ButtonDebouncerConfig debounce{};
  input::ButtonMap buttons = input::ButtonMap::paper_default();
  math::WarpMethod method = math::WarpMethod::twister;
  TurnConfig turns{};     // how far one stroke may turn (unwrapped up to 330 degrees)
  RefineConfig refine{};  // adaptive refinement at commit (off by default)
  // Every stroke mirrored or repeated about an axis (docs/math.md §11; none by default).
  // Needs SculptStorage::plan.symmetry (else a symmetric grab is refused).
  math::SymmetrySpec symmetry{};
  // The groups the symmetry_cycle chord and the cycle_symmetry command step through
  // (empty: none and `symmetry`).
  SymmetryCycle symmetry_cycle{};
};

// Caller-owned working memory, sized once at start-up.
struct SculptStorage {
  // Warped positions of the live stroke; each at least the mesh's vertex capacity.
  std::span<float> live_x;
  std::span<float> live_y;
  std::span<float> live_z;
  // capacity = most vertices one stroke may move; plan.symmetry (optional, its start
  // columns the plan's capacity): symmetric strokes.
  math::WarpPlanStorage plan;
  std::span<VertexChange> undo_changes;
  std::span<UndoEntry> undo_entries;
  // Refinement (optional; empty: commits are never refined): the refiner's memory for
  // the mesh's capacities and the undo pool of refined commits' triangles.
  mesh::MeshRefinerStorage refine{};
  std::span<TriangleChange> undo_triangle_changes{};
  // Vertex normals kept up to date (optional; each column the mesh's vertex capacity).
  mesh::NormalColumns normals{};
  // Refinement of clutch chains (optional; each column the plan's capacity; empty: a
  // chain's end is committed unrefined): the chain-start positions (ClutchChain).
  math::VertexColumns chain_start{};
};

class SculptSession {
 public:
  // `journal` may be null (no recording, e.g. the replay tool). The mesh, storage
  // and journal must outlive the session.
  SculptSession(const SculptSessionConfig& config, mesh::Mesh& mesh, SculptStorage storage,
                journal::JournalWriter* journal);
  SculptSession(const SculptSession&) = delete;
  SculptSession& operator=(const SculptSession&) = delete;

  // Raw button edge from a ports::ButtonSource. out_of_range: unknown line.
  Status feed_button(const ports::ButtonEdge& edge);
  // Whether the button device is there (ButtonSource::connected()). While it is not,
  // the hands' open strokes and moves hold and are cancelled after the lost timeout,
  // as on lost tracking (InteractionMachine); its buttons read released when it is back.
  void set_buttons_connected(bool connected) { buttons_.set_connected(connected); }
  bool buttons_connected() const { return buttons_.connected(); }
  // Latest pose of a hand (hand < kHandCount). An invalid sample means "lost".
  // invalid_argument: valid but not an orthonormal frame (treated as lost).
  Status set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world);
  // One step at `now_us`: debounced buttons, interaction machine, warp, commits,
  // then the commands of the step's button presses and those submitted since.
  SessionEvents step(ports::TimestampUs now_us);

  // Queues a command for the next step (its result comes as that step's event:
  // undone / redone / method_changed / symmetry_changed, or command_refused with the
  // reason).
  // resource_exhausted: kMaxQueuedCommands already queued; invalid_argument: hand
  // out of range.
  Status submit(const SessionCommand& command);

  // Ends what is open without committing it (the station stopping): every hand of an
  // open stroke is cancelled (the model stays as after the last commit) and an open
  // object move is cancelled (the object goes back), each with reason stopped.
  // Returns those events.
  SessionEvents cancel_open();

  // Undo / redo of committed strokes (journaled), at once, without events.
  // failed_precondition: a stroke or move is active, or there is nothing to
  // undo/redo. io_error: its record could not be saved, so the step was taken back
  // (the model is unchanged).
  Status undo();
  Status redo();

  // Applies one journal record (replay at start-up or in `twister replay`); the
  // same code path as a live commit. data_loss: the record does not fit the
  // session state (a freeze step without its chain, undo with an empty history);
  // invalid_argument / resource_exhausted: the warp plan refused the record.
  Status apply_record(const journal::JournalRecord& record);
  // Applies every good record of an opened reader; returns how many. Stops at the
  // clean end or at a torn/corrupt tail (see reader.problem(); the caller reports
  // it and calls reader.truncate_tail()). Errors of apply_record are returned.
  Result<std::size_t> replay(journal::JournalReader& reader);
  const ReplayStats& replay_stats() const { return replay_.stats(); }

  const mesh::Mesh& mesh() const { return mesh_.mesh(); }
  // Vertex normals of mesh() (mesh::compute_vertex_normals), vertex_count() long; empty
  // without normal storage. Current after construction, step(), undo(), redo() and
  // replay(); after apply_record() from the next of these.
  mesh::NormalColumns normals() const;
  const math::Frame& object_pose() const { return poses_.object(); }
  // The hands' latest samples (validity, pose in world and object frame) and their
  // debounced button levels, for the display link.
  const SessionPoses& poses() const { return poses_; }
  const input::HandButtons& hand_buttons(std::uint8_t hand) const { return buttons_.hand(hand); }
  float radius_m() const { return machine_.radius_m(); }
  const input::InteractionMachine& machine() const { return machine_; }
  LiveWarp live() const {
    LiveWarp w = strokes_.live();
    w.refine_threshold_m = refinement_.live_threshold();
    return w;
  }
  // The open stroke's warped positions where live().plan->indices() (see
  // StrokeController::live_positions()).
  math::ConstVertexColumns live_positions() const { return strokes_.live_positions(); }
  // What the display shows besides mesh and live warp (see SessionState).
  SessionState state() const;
  math::WarpMethod method() const { return strokes_.method(); }
  // The symmetry group of the next strokes (SculptSessionConfig::symmetry).
  math::SymmetrySpec symmetry() const { return strokes_.symmetry(); }
  Status set_symmetry(const math::SymmetrySpec& spec) { return strokes_.set_symmetry(spec); }
  bool busy() const { return strokes_.active() || mover_.moving(); }  // stroke or move
  std::uint32_t next_sequence() const { return history_.next_sequence(); }
  const UndoHistory& history() const { return history_.undo_history(); }

  // For SessionCheckpoint's restore only: the state a checkpoint holds (mesh counts,
  // positions and triangles, undo history, object pose, next sequence), as parts to
  // write into; then checkpoint_restored() recomputes what derives from the model
  // (vertex normals).
  struct RestoreTarget {
    mesh::Mesh& mesh;
    UndoHistory& history;
    SessionPoses& poses;
    SessionHistory& commits;
  };
  RestoreTarget restore_target() { return {mesh_.mesh(), history_.restorable(), poses_, history_}; }
  void checkpoint_restored();
  // Exhibit rotation (issue 25): the model becomes `base` again (same vertices,
  // triangles), the undo history is emptied, the object pose is the identity and
  // records are numbered from 0 (a new journal). Only between strokes (busy() false):
  // failed_precondition otherwise; invalid_argument/resource_exhausted: `base` does
  // not fit the mesh's capacity (nothing changed).
  Status reset_model(const mesh::Mesh& base);

 private:
  void apply_action(const input::Action& action, SessionEvents& out);
  void commit_move(const input::Action& action, SessionEvents& out);
  input::InteractionInputs inputs() const;
  // undo() (type undo) or redo() (type redo).
  Status step_history(journal::RecordType type);
  void run_command(const SessionCommand& command, SessionEvents& out);
  void run_history_command(const SessionCommand& command, SessionEvents& out);
  void run_symmetry_command(const SessionCommand& command, SessionEvents& out);
  // Recomputes the normals when the model changed since they were computed.
  void refresh_normals();

  LiveMesh mesh_;
  CommitRefinement refinement_;
  SessionPoses poses_;
  input::ButtonFrontEnd buttons_;
  input::InteractionMachine machine_;
  // The one plan (one WarpPlanStorage): the live strokes' and, while none is open,
  // the replay's; a replayed freeze step continues the plan of the record before it.
  math::WarpPlan plan_;
  SessionHistory history_;
  StrokeController strokes_;
  ObjectMover mover_;
  JournalReplay replay_;
  InlineVector<SessionCommand, kMaxQueuedCommands> queued_;
  mesh::NormalColumns normals_{};
  std::uint32_t normals_sequence_ = 0;  // next_sequence() when they were computed
  SymmetryCycle symmetry_cycle_{};      // resolved against the configured symmetry
};

namespace internal {
// Three float columns of N each (a clutch chain's start).
template <std::size_t N>
struct FloatColumns {
  std::array<float, N> x{};
  std::array<float, N> y{};
  std::array<float, N> z{};
};
// Symmetric strokes' plan storage: the warp, each plan vertex's chain-start position and
// the float path's order and weights (PlanSymmetry's spans point into them: not copyable).
template <std::size_t N>
struct SymmetryArrays {
  SymmetryArrays() = default;
  SymmetryArrays(const SymmetryArrays&) = delete;
  SymmetryArrays& operator=(const SymmetryArrays&) = delete;
  FloatColumns<N> start{};
  // The float path's sorted order and kept weights (docs/math.md §11.7).
  std::array<std::uint64_t, math::SymmetricFloat::words_for(N)> balls{};
  std::array<float, math::SymmetricFloat::weights_for(N)> weights{};
  math::PlanSymmetry plan{{}, math::VertexColumns{start.x, start.y, start.z}, balls, weights};
};
}  // namespace internal

// A session owning its working memory: kVertices = mesh vertex capacity,
// kInfluenced = plan capacity, kUndoChanges / kUndoEntries = history size,
// kTriangles = mesh triangle capacity for refinement (0: no refinement memory; else
// also kUndoChanges triangle changes for its undo, vertex normals and kInfluenced
// chain-start positions for clutch chains).
// Large: place it in static storage or the start-up arena.
template <std::size_t kVertices, std::size_t kInfluenced, std::size_t kUndoChanges,
          std::size_t kUndoEntries, std::size_t kTriangles = 0>
struct SculptStorageArrays {
  static constexpr std::size_t kRefineVertices = kTriangles == 0 ? 0 : kVertices;
  static constexpr std::size_t kTriangleChanges = kTriangles == 0 ? 0 : kUndoChanges;
  static constexpr std::size_t kChainVertices = kTriangles == 0 ? 0 : kInfluenced;
  std::array<float, kVertices> live_x{};
  std::array<float, kVertices> live_y{};
  std::array<float, kVertices> live_z{};
  std::array<std::uint32_t, kInfluenced> plan_indices{};
  std::array<float, kInfluenced> plan_weights1{};
  std::array<float, kInfluenced> plan_weights2{};
  std::array<VertexChange, kUndoChanges> undo_changes{};
  std::array<UndoEntry, kUndoEntries> undo_entries{};
  mesh::internal::MeshRefinerArrays<kRefineVertices, kTriangles> refiner{};
  std::array<TriangleChange, kTriangleChanges> undo_triangle_changes{};
  std::array<float, kRefineVertices> normal_x{};
  std::array<float, kRefineVertices> normal_y{};
  std::array<float, kRefineVertices> normal_z{};
  internal::FloatColumns<kChainVertices> chain_start{};
  internal::SymmetryArrays<kInfluenced> symmetry{};

  SculptStorage spans() {
    return SculptStorage{
        live_x,
        live_y,
        live_z,
        math::WarpPlanStorage{plan_indices, plan_weights1, plan_weights2, &symmetry.plan},
        undo_changes,
        undo_entries,
        refiner.spans(),
        undo_triangle_changes,
        mesh::NormalColumns{normal_x, normal_y, normal_z},
        math::VertexColumns{chain_start.x, chain_start.y, chain_start.z}};
  }
};

template <std::size_t kVertices, std::size_t kInfluenced, std::size_t kUndoChanges,
          std::size_t kUndoEntries, std::size_t kTriangles = 0>
class SculptSessionWithStorage
    : private SculptStorageArrays<kVertices, kInfluenced, kUndoChanges, kUndoEntries, kTriangles>,
      public SculptSession {
 public:
  SculptSessionWithStorage(const SculptSessionConfig& config, mesh::Mesh& mesh,
                           journal::JournalWriter* journal)
      : SculptSession(config, mesh, this->spans(), journal) {}
};

}  // namespace twister::session
