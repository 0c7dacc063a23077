// SessionState: what a display shows about a SculptSession besides the mesh and the
// live warp (SculptSession::state(), a snapshot after the last step): the radius and
// whether the radius gesture is on, the warp method and turn tracking, the undo/redo
// depths, and per hand its state, buttons, clutch and how far it has turned in its
// stroke against the limit. Events (SessionEvents) say when these change; this is
// the state to draw at any time. Plain data.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/input/button_map.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/session/commit_refinement.hpp"
#include "twister/session/hand_drive.hpp"

namespace twister::session {

struct HandView {
  input::HandState state = input::HandState::idle;
  input::HandButtons buttons{};  // role levels after debounce and chords
  bool tracked = false;          // the hand's latest sample is valid
  bool in_stroke = false;        // the hand grabs in the open stroke segment
  bool engaged = true;           // false: clutch in (freeze held), the hand's motion does not warp
  double turn_rad = 0.0;         // how far the hand has turned since its segment started
  double turn_limit_rad = 0.0;   // the limit of one stroke (a half turn when minimal)
  bool at_turn_limit = false;    // turned past the limit: the warp holds
};

// The symmetry groups (docs/math.md §11): of the next stroke, of the open one.
struct SymmetryView {
  math::SymmetrySpec next{};
  math::SymmetrySpec stroke{};
};

struct SessionState {
  float radius_m = 0.0f;
  bool radius_gesture_enabled = true;
  bool radius_gesture_active = false;  // both radius buttons held: the radius follows
  math::WarpMethod method = math::WarpMethod::twister;  // of the next stroke
  TurnTracking turn_tracking = TurnTracking::unwrapped;
  bool stroke_active = false;
  math::WarpMethod stroke_method = math::WarpMethod::twister;  // of the open stroke
  SymmetryView symmetry{};       // of the next and the open stroke (docs/math.md §11)
  std::uint16_t chain_step = 0;  // freeze steps of the open stroke so far
  bool moving_object = false;
  std::size_t undo_depth = 0;
  std::size_t redo_depth = 0;
  std::uint32_t next_sequence = 0;  // journal records so far
  std::array<HandView, input::kHandCount> hands{};
  RefineStatus refine{};  // refinement: on, threshold, spare capacity, the last stop
};

}  // namespace twister::session
