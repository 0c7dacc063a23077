// InteractionMachine: the one explicit state machine of the sculpting interaction
// (docs/math.md §8; diagram in docs/interaction.md).
// Per hand: idle -> dragging (grab pressed: start pose recorded, warp plan built)
// -> idle (grab released: commit). Freeze is a clutch inside a drag (the paper's
// freeze): pressing it commits the warp and disengages the hand (its motion no longer
// warps; selection and weights stay), releasing it re-engages the hand from where it
// is then. dragging -> dragging_lost when tracking drops: the warp holds at the last
// valid pose; tracking back within lost_timeout_us resumes, otherwise the stroke is
// cancelled (not while disengaged: a hand on the clutch may leave the tracked volume).
// A button device that vanishes (HandInput::buttons_valid false) is lost tracking for
// every stroke or move open then: the hand's levels hold as they were (no edge can
// come from a device that is not there), the warp holds at the last valid pose and
// the stroke is cancelled after lost_timeout_us (tracking_timeout), clutch in or not;
// such a stroke does not resume even if the device comes back in time (its buttons'
// levels meanwhile are unknown).
// moving / moving_lost are the same for the rigid object move.
// Both hands run the same per-hand machine; the two-handed radius gesture is a
// small combiner on top (both radius buttons held, both hands idle).
// Pure: step(inputs, now) -> actions. No clock, no I/O, no allocation.
// Positions are in metres, in the world (tracker) frame.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/input/button_map.hpp"
#include "twister/ports/clock.hpp"

namespace twister::input {

enum class HandState : std::uint8_t { idle = 0, dragging, dragging_lost, moving, moving_lost };
inline constexpr std::uint8_t kHandStateCount = 5;

enum class ActionKind : std::uint8_t {
  grab_begin,        // start a stroke for `hand` from its current pose
  freeze,            // clutch in: commit the stroke; the hand disengages (same weights)
  commit,            // grab released: commit the stroke (at the last valid pose if lost)
  cancel,            // stroke dropped, model unchanged (reason tracking_timeout)
  tracking_lost,     // live warp holds at the last valid pose
  tracking_resumed,  // the stroke continues from the live pose
  move_begin,        // start moving the object rigidly with `hand`
  move_commit,
  move_cancel,
  radius_begin,   // both radius buttons held: radius follows the hand distance
  radius_change,  // radius_m holds the new, clamped radius
  radius_end,
  refused,   // a press was not accepted; `reason` says why
  unfreeze,  // clutch out: the disengaged hand warps again from its current pose
};

enum class Reason : std::uint8_t {
  none = 0,
  released,          // the user released the button
  tracking_timeout,  // tracking stayed lost longer than lost_timeout_us
  no_tracking,       // press while the hand's pose is not valid
  same_point,        // second grab at the other hand's grab point (|OQ| ~ 0)
  hand_busy,         // the hand already grabs or moves the object
  object_busy,       // the other hand already moves the object
  hands_too_close,   // radius gesture with the hands (almost) together
  busy,              // a command (undo, redo, method) while a stroke or move is open
  nothing_to_undo,   // undo with an empty history
  nothing_to_redo,   // redo with nothing undone
  stopped,           // cancelled from outside: the station stops (SculptSession::cancel_open)
  not_available,     // a command whose feature is off here (no exhibit, no symmetry cycle)
};

const char* action_kind_name(ActionKind kind);
const char* reason_name(Reason reason);

struct Action {
  ActionKind kind = ActionKind::refused;
  std::uint8_t hand = 0;
  Reason reason = Reason::none;
  float radius_m = 0.0f;  // radius_* actions: the radius after the action
};

inline constexpr std::size_t kMaxActionsPerStep = 8;

// The actions of one step, in the order they must be applied.
class ActionList {
 public:
  void push(const Action& action);
  std::span<const Action> items() const { return items_; }
  std::size_t size() const { return items_.size(); }

 private:
  InlineVector<Action, kMaxActionsPerStep> items_;
};

struct HandInput {
  bool pose_valid = false;
  glm::vec3 position_m{0.0f};  // world frame; ignored when !pose_valid
  HandButtons buttons{};       // debounced levels
  bool buttons_valid = true;   // false: the button device is missing (levels unknown)
};

struct InteractionInputs {
  std::array<HandInput, kHandCount> hands{};
};

struct InteractionConfig {
  ports::TimestampUs lost_timeout_us = 500'000;
  float min_grab_separation_m = 0.01f;  // closer second grab: refused (same_point)
  float radius_min_m = 0.02f;
  float radius_max_m = 2.0f;
  float initial_radius_m = 0.25f;
  bool radius_gesture = true;  // false: the radius buttons do nothing
};

class InteractionMachine {
 public:
  // The initial radius is clamped into [radius_min_m, radius_max_m].
  explicit InteractionMachine(const InteractionConfig& config);

  // Advances both hands and the radius gesture by one step. `now_us` must not go
  // backwards. Every grab_begin of a hand is followed by exactly one commit or
  // cancel of that hand (the same for move_begin / move_commit / move_cancel).
  ActionList step(const InteractionInputs& inputs, ports::TimestampUs now_us);

  HandState state(std::uint8_t hand) const { return hands_[hand].state; }
  // The hand's clutch is in (freeze held during its stroke): its motion does not warp.
  bool disengaged(std::uint8_t hand) const { return hands_[hand].disengaged; }
  ports::TimestampUs state_since_us(std::uint8_t hand) const { return hands_[hand].since_us; }
  float radius_m() const { return radius_m_; }
  bool radius_active() const { return radius_ == RadiusGesture::active; }
  const InteractionConfig& config() const { return config_; }

 private:
  enum class RadiusGesture : std::uint8_t { off, active, refused };
  struct Hand {
    HandState state = HandState::idle;
    ports::TimestampUs since_us = 0;
    HandButtons previous{};
    glm::vec3 last_valid_m{0.0f};
    bool disengaged = false;    // freeze held during the stroke (dragging states only)
    bool buttons_gone = false;  // its button device vanished during this stroke or move
  };

  // One hand's step: its button edges and input, read once before any transition.
  struct HandStep {
    std::uint8_t hand;
    const HandInput& in;
    bool grab_pressed;
    bool move_pressed;
    bool freeze_pressed;
    ports::TimestampUs now_us;
  };

  // step_hand dispatches on the hand's state to one function per HandState.
  void step_hand(std::uint8_t h, const HandInput& in, ports::TimestampUs now_us, ActionList& out);
  // The input as the machine reads it: a hand whose button device is missing (or
  // vanished during its open stroke or move) is lost, its buttons as they were.
  InteractionInputs effective(const InteractionInputs& inputs);
  void step_idle(const HandStep& s, ActionList& out);
  void step_dragging(const HandStep& s, ActionList& out);
  void step_dragging_lost(const HandStep& s, ActionList& out);
  void step_moving(const HandStep& s, ActionList& out);
  void step_moving_lost(const HandStep& s, ActionList& out);
  bool lost_too_long(const HandStep& s) const;
  void step_radius(const InteractionInputs& inputs, ActionList& out);
  void enter(std::uint8_t h, HandState state, ports::TimestampUs now_us);
  // The grab ends (released: commit, or cancel); the clutch goes with it.
  void end_grab(const HandStep& s, ActionKind kind, Reason reason, ActionList& out);
  bool other_hand_grabs_near(std::uint8_t h, glm::vec3 position_m) const;

  InteractionConfig config_;
  std::array<Hand, kHandCount> hands_{};
  float radius_m_;
  RadiusGesture radius_ = RadiusGesture::off;
  float radius_start_m_ = 0.0f;
  float radius_start_distance_m_ = 0.0f;
};

}  // namespace twister::input
