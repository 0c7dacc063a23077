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
// constant. Release commits it; freeze commits it and rebases the plan (same
// vertices and weights, chain_step + 1); a hand joining or leaving commits the
// segment and starts a new one for the hands that still grab. A cancel (tracking
// lost too long) drops the open segment: the model stays as at its start.
// Each commit is one journal record (synced) and one undo entry.
//
// Memory: everything comes from SculptStorage given at construction (see
// SculptSessionWithStorage); no heap allocation ever. Not thread-safe: call from
// the station's poll loop only. Time in microseconds on a monotonic clock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/input/button_debouncer.hpp"
#include "twister/input/button_front_end.hpp"
#include "twister/input/button_map.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/input/object_mover.hpp"
#include "twister/input/session_events.hpp"
#include "twister/input/session_poses.hpp"
#include "twister/input/undo_history.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"

namespace twister::input {

// History size the station uses unless configured otherwise. A replay tool must use
// the same sizes to reproduce undo records exactly once the history has overflowed.
inline constexpr std::size_t kDefaultUndoChanges = std::size_t{1} << 18;
inline constexpr std::size_t kDefaultUndoEntries = 64;

struct SculptSessionConfig {
  InteractionConfig interaction{};
  ButtonDebouncerConfig debounce{};
  ButtonMap buttons = ButtonMap::paper_default();
  math::WarpMethod method = math::WarpMethod::twister;
};

// Caller-owned working memory, sized once at start-up.
struct SculptStorage {
  // Warped positions of the live stroke; each at least the mesh's vertex capacity.
  std::span<float> live_x;
  std::span<float> live_y;
  std::span<float> live_z;
  math::WarpPlanStorage plan;  // capacity = most vertices one stroke may move
  std::span<VertexChange> undo_changes;
  std::span<UndoEntry> undo_entries;
};

// What a display needs for the live stroke (valid while active).
struct LiveWarp {
  bool active = false;
  std::uint8_t hand_mask = 0;            // session hands in the stroke (bit h)
  const math::WarpPlan* plan = nullptr;  // indices, weights, screws, start/end frames
  math::ConstVertexColumns positions;    // live_x/y/z: warped where plan->indices()
};

struct ReplayStats {
  std::size_t strokes = 0;
  std::size_t moves = 0;
  std::size_t undos = 0;
  std::size_t redos = 0;
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
  // Latest pose of a hand (hand < kHandCount). An invalid sample means "lost".
  // invalid_argument: valid but not an orthonormal frame (treated as lost).
  Status set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world);
  // One step at `now_us`: debounced buttons, interaction machine, warp, commits.
  SessionEvents step(ports::TimestampUs now_us);

  // Undo / redo of committed strokes (journaled). failed_precondition: a stroke or
  // move is active, or there is nothing to undo/redo. io_error: journal failed
  // (the undo itself happened).
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
  const ReplayStats& replay_stats() const { return replay_stats_; }

  const mesh::Mesh& mesh() const { return mesh_; }
  const math::Frame& object_pose() const { return poses_.object(); }
  float radius_m() const { return machine_.radius_m(); }
  const InteractionMachine& machine() const { return machine_; }
  LiveWarp live() const;
  bool busy() const;  // a stroke or move is active
  std::uint32_t next_sequence() const { return next_sequence_; }
  const UndoHistory& history() const { return history_; }

 private:
  void apply_action(const Action& action, SessionEvents& out);
  Status begin_segment(std::uint8_t hand_mask);
  // Commits the open segment; the committed event names `hand` and `reason`
  // (released: the hand's grab ends; none: the stroke continues). Returns that event.
  SessionEvent commit_segment(std::uint8_t hand, Reason reason, SessionEvents& out);
  // Reports the grabs of `mask` as ended (cancelled with `status`).
  void end_hands(std::uint8_t mask, Status status, SessionEvents& out);
  void restart_without(std::uint8_t hand, bool commit, SessionEvents& out);
  Status update_plan();
  Status commit_plan(const journal::JournalRecord& record, bool journaled, SessionEvents* out);
  void journal_append(journal::JournalRecord& record, SessionEvents* out);
  // undo() (type undo) or redo() (type redo): the step on the mesh, then its record.
  Status step_history(journal::RecordType type);
  std::size_t plan_frames(std::array<math::Frame, 2>& frames) const;
  math::ConstVertexColumns rest() const;
  math::VertexColumns live_columns();

  SculptSessionConfig config_;
  mesh::Mesh& mesh_;
  SculptStorage storage_;
  journal::JournalWriter* journal_;
  SessionPoses poses_;
  ButtonFrontEnd buttons_;
  InteractionMachine machine_;
  math::WarpPlan plan_;
  UndoHistory history_;
  // Open stroke segment.
  std::uint8_t stroke_mask_ = 0;
  std::uint16_t chain_step_ = 0;
  bool segment_moved_ = false;  // a step has passed since the segment began
  double stroke_radius_m_ = 0.0;
  std::array<math::Frame, 2> stroke_start_{};  // object frame, per plan hand
  ObjectMover mover_;
  std::uint32_t next_sequence_ = 0;
  // Hands whose grab the machine ends with a commit in the current step: released
  // together, they share one commit instead of one hand "continuing" for no time.
  std::uint8_t releasing_mask_ = 0;
  bool replay_chain_open_ = false;  // replay: a stroke chain may continue (freeze)
  std::uint16_t replay_chain_step_ = 0;
  ReplayStats replay_stats_{};
};

// A session owning its working memory: kVertices = mesh vertex capacity,
// kInfluenced = plan capacity, kUndoChanges / kUndoEntries = history size.
// Large: place it in static storage or the start-up arena.
template <std::size_t kVertices, std::size_t kInfluenced, std::size_t kUndoChanges,
          std::size_t kUndoEntries>
struct SculptStorageArrays {
  std::array<float, kVertices> live_x{};
  std::array<float, kVertices> live_y{};
  std::array<float, kVertices> live_z{};
  std::array<std::uint32_t, kInfluenced> plan_indices{};
  std::array<float, kInfluenced> plan_weights1{};
  std::array<float, kInfluenced> plan_weights2{};
  std::array<VertexChange, kUndoChanges> undo_changes{};
  std::array<UndoEntry, kUndoEntries> undo_entries{};

  SculptStorage spans() {
    return SculptStorage{
        live_x,       live_y,
        live_z,       math::WarpPlanStorage{plan_indices, plan_weights1, plan_weights2},
        undo_changes, undo_entries};
  }
};

template <std::size_t kVertices, std::size_t kInfluenced, std::size_t kUndoChanges,
          std::size_t kUndoEntries>
class SculptSessionWithStorage
    : private SculptStorageArrays<kVertices, kInfluenced, kUndoChanges, kUndoEntries>,
      public SculptSession {
 public:
  SculptSessionWithStorage(const SculptSessionConfig& config, mesh::Mesh& mesh,
                           journal::JournalWriter* journal)
      : SculptSession(config, mesh, this->spans(), journal) {}
};

}  // namespace twister::input
