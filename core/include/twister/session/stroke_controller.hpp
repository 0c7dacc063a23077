// StrokeController: the warp strokes of a session. It turns the machine's stroke
// actions (grab_begin, freeze, unfreeze, commit, cancel) into the WarpPlan's lifecycle
// and hands every commit to a StrokeCommitSink.
//
// A stroke segment is a period in which the set of grabbing hands is constant: one
// plan, built from the hands' poses when it begins. Release commits it; a hand joining
// or leaving commits the segment and starts a new one for the hands that still grab;
// hands released in the same step share one commit. A cancel (tracking lost too long)
// drops the open segment only. Between actions, end_step() moves the plan to the
// hands' end poses: its screws, which is all the display's live stream carries.
// The live warp on demand (issue 24): no vertex is warped on the CPU between commits.
// The display warps the live stroke itself (the vertex shader; scodef, which has no
// per-vertex closed form, on the bridge's CPU from the same messages), so nothing on
// the station needs the warped positions per tracker record. live_positions() warps
// the plan's vertices into the live columns when a consumer asks (at most once per
// plan move), and a commit warps them once, at the end poses, with the same kernel:
// the model is bit-for-bit what a warp at every step would have made of it.
// Freeze is the paper's clutch: pressing it commits the segment and rebases the plan
// (same vertices and weights, chain step + 1) with the hand disengaged, so moving it
// changes nothing; releasing it rebases again from the poses of that moment and the
// hand drives the warp again (no commit, unless another hand of the segment could have
// warped meanwhile or the segment was built while the hand was disengaged). Three
// 120-degree twists with the hand turned back in between make a 360-degree twist.
// A disengaged hand in a segment built or rebased meanwhile (another hand joining,
// leaving or freezing) keeps its anchor: the pose it disengaged at.
// A commit that is not saved (write-ahead journal full or failing) is reported as
// not_saved and changes nothing; at a freeze press or release (a chain step) it ends
// the stroke for every hand of the segment, so a chain never skips a step.
// How a hand's motion becomes its end pose (the clutch, turns past a half turn, the
// turn limit) is its HandDrive. Hand poses are taken in the object frame at the
// moment they are used. No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/vertex_columns.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/session/hand_drive.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/session_events.hpp"
#include "twister/session/session_poses.hpp"
#include "twister/session/stroke_commit_sink.hpp"

namespace twister::session {

// What a display needs for the live stroke (valid while active). The warped positions
// are not part of it: StrokeController::live_positions() computes them when asked.
struct LiveWarp {
  bool active = false;
  std::uint8_t hand_mask = 0;            // session hands in the stroke (bit h)
  const math::WarpPlan* plan = nullptr;  // indices, weights, screws, start/end frames
  double refine_threshold_m = 0.0;       // the commit's refinement (0: none), for the preview
};

class StrokeController {
 public:
  // Every reference must outlive the controller. `plan` is reset whenever no stroke
  // is open; between strokes its owner may use it (journal replay does).
  StrokeController(math::WarpPlan& plan, LiveMesh& mesh, const SessionPoses& poses,
                   StrokeCommitSink& commits, math::WarpMethod method,
                   const TurnConfig& turns = {});
  StrokeController(const StrokeController&) = delete;
  StrokeController& operator=(const StrokeController&) = delete;

  // Before applying one step's actions: notes which hands `actions` release (they
  // end with one shared commit) and the radius new segments are built with.
  void begin_step(const input::ActionList& actions, float radius_m);
  // Applies one stroke action of the step (grab_begin, freeze, unfreeze, commit,
  // cancel; other kinds are ignored). Events go to `out` in the order they happen.
  void apply(const input::Action& action, SessionEvents& out);
  // After the step's actions: the open segment follows the hands' current poses
  // (turn_limit_reached / turn_limit_left events to `out`).
  void end_step(SessionEvents& out);
  void end_step() {
    SessionEvents ignored;
    end_step(ignored);
  }

  // The method of segments begun from now on (the open one keeps its own).
  void set_method(math::WarpMethod method) { method_ = method; }
  math::WarpMethod method() const { return method_; }
  // The symmetry group of segments begun from now on (docs/math.md §11; the open one
  // keeps its own). invalid_argument (unchanged) unless math::valid_symmetry(spec).
  Status set_symmetry(const math::SymmetrySpec& spec) { return symmetry_.set(spec); }
  math::SymmetrySpec symmetry() const { return symmetry_.spec(); }

  bool active() const { return hand_mask_ != 0; }
  std::uint8_t hand_mask() const { return hand_mask_; }
  std::uint16_t chain_step() const { return chain_step_; }
  // Hand h's drive (clutch, turn, limit); meaningful while h is in the stroke.
  const HandDrive& drive(std::uint8_t hand) const { return drives_[hand]; }
  LiveWarp live() const;
  // The live columns (live_x/y/z, vertex_count() long): the open stroke's warped
  // positions where plan->indices(), meaningful while active(). Computed here, on
  // demand: the first call after the plan moved (a step, a segment begun or rebased)
  // warps the plan's vertices (the cost of one WarpPlan::apply), later calls return
  // them as they are. Logically const (a cache of the plan's warp of the rest mesh).
  math::ConstVertexColumns live_positions() const;

 private:
  void grab(std::uint8_t hand, SessionEvents& out);
  void freeze(std::uint8_t hand, SessionEvents& out);
  void unfreeze(std::uint8_t hand, SessionEvents& out);
  // A hand's grab ends (commit: released; else cancelled): the segment of the other
  // hands goes on as a new segment.
  void end_grab(std::uint8_t hand, bool commit, input::Reason cancel_reason, SessionEvents& out);
  Status begin_segment(std::uint8_t mask);
  // Rebases the open segment on the hands' current poses (same weights); the chain
  // step advances when `committed`. On failure the stroke ends (cancelled events).
  void restart_segment(bool committed, SessionEvents& out);
  // Commits the open segment; the committed event names `hand` and `reason`
  // (released: the hand's grab ends; none: the stroke continues), or, when the commit
  // did not happen, a not_saved event with `reason_if_not_saved`. `plan_goes_on`: a
  // freeze step, the plan is rebased next (no refinement). Returns that event.
  SessionEvent commit_segment(std::uint8_t hand, input::Reason reason, SessionEvents& out,
                              input::Reason reason_if_not_saved, bool plan_goes_on = false);
  // A chain step (freeze or unfreeze) of `hand` was not saved (`failed`): the stroke
  // ends for every hand of the segment (not_saved repeats for the others).
  void end_not_saved(std::uint8_t hand, const SessionEvent& failed, SessionEvents& out);
  // Some hand of the open segment is engaged: the segment may have warped something.
  bool segment_can_change() const;
  // Reports the grabs of `mask` as ended (cancelled with `status`).
  void end_hands(std::uint8_t mask, Status status, SessionEvents& out);
  void drop_segment();
  Status update_plan(SessionEvents* out);
  // The start poses of a (re)started segment, in the object frame, in plan order: an
  // engaged hand's drive starts at its current pose, a disengaged hand keeps its
  // anchor (the pose it disengaged at).
  math::PlanFrames start_drives();
  // The plan moved (or the segment changed): the live columns are out of date.
  void plan_moved() { live_current_ = false; }

  math::WarpPlan& plan_;
  LiveMesh& mesh_;
  const SessionPoses& poses_;
  StrokeCommitSink& commits_;
  math::WarpMethod method_;
  math::SymmetryGroup symmetry_{};  // of new segments
  float radius_m_ = 0.0f;           // the machine's radius in the current step
  std::array<HandDrive, input::kHandCount> drives_;
  // Open stroke segment.
  std::uint8_t hand_mask_ = 0;
  std::uint16_t chain_step_ = 0;
  bool segment_moved_ = false;  // a step has passed since the segment began
  double segment_radius_m_ = 0.0;
  std::uint32_t last_sequence_ = 0;  // of the last commit (a grab ending without one)
  // Hands whose grab the machine ends with a commit in the current step: released
  // together, they share one commit instead of one hand "continuing" for no time.
  std::uint8_t releasing_mask_ = 0;
  // The live columns hold the plan's current warp (live_positions() since plan_moved()).
  mutable bool live_current_ = false;
};

}  // namespace twister::session
