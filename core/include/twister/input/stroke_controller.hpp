// StrokeController: the warp strokes of a session. It turns the machine's stroke
// actions (grab_begin, freeze, commit, cancel) into the WarpPlan's lifecycle and
// hands every commit to a StrokeCommitSink.
//
// A stroke segment is a period in which the set of grabbing hands is constant: one
// plan, built from the hands' poses when it begins. Release commits it; freeze
// commits it and rebases the plan (same vertices and weights, chain step + 1); a hand
// joining or leaving commits the segment and starts a new one for the hands that still
// grab; hands released in the same step share one commit. A cancel (tracking lost too
// long) drops the open segment only. Between actions, end_step() moves the plan to the
// hands' current poses and writes the warped positions into the live columns.
// Hand poses are taken in the object frame at the moment they are used.
//
// Extension point: how hand motion becomes the plan's end poses (plan_frames) and
// what freeze does to a hand belong here. No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/input/live_mesh.hpp"
#include "twister/input/session_events.hpp"
#include "twister/input/session_poses.hpp"
#include "twister/input/stroke_commit_sink.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/vertex_columns.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::input {

// What a display needs for the live stroke (valid while active).
struct LiveWarp {
  bool active = false;
  std::uint8_t hand_mask = 0;            // session hands in the stroke (bit h)
  const math::WarpPlan* plan = nullptr;  // indices, weights, screws, start/end frames
  math::ConstVertexColumns positions;    // live_x/y/z: warped where plan->indices()
};

class StrokeController {
 public:
  // Every reference must outlive the controller. `plan` is reset whenever no stroke
  // is open; between strokes its owner may use it (journal replay does).
  StrokeController(math::WarpPlan& plan, LiveMesh& mesh, const SessionPoses& poses,
                   StrokeCommitSink& commits, math::WarpMethod method);
  StrokeController(const StrokeController&) = delete;
  StrokeController& operator=(const StrokeController&) = delete;

  // Before applying one step's actions: notes which hands `actions` release (they
  // end with one shared commit) and the radius new segments are built with.
  void begin_step(const ActionList& actions, float radius_m);
  // Applies one stroke action of the step (grab_begin, freeze, commit, cancel; other
  // kinds are ignored). Events go to `out` in the order they happen.
  void apply(const Action& action, SessionEvents& out);
  // After the step's actions: the open segment follows the hands' current poses.
  void end_step();

  bool active() const { return hand_mask_ != 0; }
  std::uint8_t hand_mask() const { return hand_mask_; }
  std::uint16_t chain_step() const { return chain_step_; }
  LiveWarp live() const;

 private:
  void grab(std::uint8_t hand, SessionEvents& out);
  void freeze(std::uint8_t hand, SessionEvents& out);
  // A hand's grab ends (commit: released; else cancelled): the segment of the other
  // hands goes on as a new segment.
  void end_grab(std::uint8_t hand, bool commit, SessionEvents& out);
  Status begin_segment(std::uint8_t mask);
  // Commits the open segment; the committed event names `hand` and `reason`
  // (released: the hand's grab ends; none: the stroke continues), or, when the commit
  // did not happen, a not_saved event with `reason_if_not_saved`. Returns that event.
  SessionEvent commit_segment(std::uint8_t hand, Reason reason, SessionEvents& out,
                              Reason reason_if_not_saved);
  // Reports the grabs of `mask` as ended (cancelled with `status`).
  static void end_hands(std::uint8_t mask, Status status, SessionEvents& out);
  void drop_segment();
  Status update_plan();
  // The poses of the segment's hands, in the object frame, in plan order.
  std::size_t plan_frames(std::array<math::Frame, 2>& frames) const;

  math::WarpPlan& plan_;
  LiveMesh& mesh_;
  const SessionPoses& poses_;
  StrokeCommitSink& commits_;
  math::WarpMethod method_;
  float radius_m_ = 0.0f;  // the machine's radius in the current step
  // Open stroke segment.
  std::uint8_t hand_mask_ = 0;
  std::uint16_t chain_step_ = 0;
  bool segment_moved_ = false;  // a step has passed since the segment began
  double segment_radius_m_ = 0.0;
  std::array<math::Frame, 2> segment_start_{};  // object frame, per plan hand
  // Hands whose grab the machine ends with a commit in the current step: released
  // together, they share one commit instead of one hand "continuing" for no time.
  std::uint8_t releasing_mask_ = 0;
};

}  // namespace twister::input
