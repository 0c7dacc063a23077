#include "twister/input/interaction_machine.hpp"

#include <algorithm>
#include <glm/geometric.hpp>

#include "twister/base/assert.hpp"

namespace twister::input {

const char* action_kind_name(ActionKind kind) {
  switch (kind) {
    case ActionKind::grab_begin:
      return "grab_begin";
    case ActionKind::freeze:
      return "freeze";
    case ActionKind::commit:
      return "commit";
    case ActionKind::cancel:
      return "cancel";
    case ActionKind::tracking_lost:
      return "tracking_lost";
    case ActionKind::tracking_resumed:
      return "tracking_resumed";
    case ActionKind::move_begin:
      return "move_begin";
    case ActionKind::move_commit:
      return "move_commit";
    case ActionKind::move_cancel:
      return "move_cancel";
    case ActionKind::radius_begin:
      return "radius_begin";
    case ActionKind::radius_change:
      return "radius_change";
    case ActionKind::radius_end:
      return "radius_end";
    case ActionKind::refused:
      return "refused";
    case ActionKind::unfreeze:
      return "unfreeze";
  }
  return "unknown";
}

const char* reason_name(Reason reason) {
  switch (reason) {
    case Reason::none:
      return "none";
    case Reason::released:
      return "released";
    case Reason::tracking_timeout:
      return "tracking_timeout";
    case Reason::no_tracking:
      return "no_tracking";
    case Reason::same_point:
      return "same_point";
    case Reason::hand_busy:
      return "hand_busy";
    case Reason::object_busy:
      return "object_busy";
    case Reason::hands_too_close:
      return "hands_too_close";
    case Reason::busy:
      return "busy";
    case Reason::nothing_to_undo:
      return "nothing_to_undo";
    case Reason::nothing_to_redo:
      return "nothing_to_redo";
    case Reason::stopped:
      return "stopped";
    case Reason::not_available:
      return "not_available";
  }
  return "unknown";
}

void ActionList::push(const Action& action) {
  // Two hands produce at most three actions each plus one radius action per step.
  const Status pushed = items_.push_back(action);
  TWISTER_ASSERT(pushed.ok());
}

InteractionMachine::InteractionMachine(const InteractionConfig& config)
    : config_(config),
      radius_m_(std::clamp(config.initial_radius_m, config.radius_min_m, config.radius_max_m)) {}

void InteractionMachine::enter(std::uint8_t h, HandState state, ports::TimestampUs now_us) {
  hands_[h].state = state;
  hands_[h].since_us = now_us;
  if (state == HandState::idle) hands_[h].buttons_gone = false;
}

bool InteractionMachine::other_hand_grabs_near(std::uint8_t h, glm::vec3 position_m) const {
  const Hand& other = hands_[1 - h];
  if (other.state != HandState::dragging && other.state != HandState::dragging_lost) return false;
  // A new grab restarts the other hand's stroke from its current (last valid)
  // pose, so that is the point the squash would divide by.
  return glm::distance(other.last_valid_m, position_m) < config_.min_grab_separation_m;
}

InteractionInputs InteractionMachine::effective(const InteractionInputs& inputs) {
  InteractionInputs in = inputs;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    Hand& hand = hands_[h];
    if (!in.hands[h].buttons_valid && hand.state != HandState::idle) hand.buttons_gone = true;
    if (!in.hands[h].buttons_valid || hand.buttons_gone) {
      in.hands[h].pose_valid = false;
      in.hands[h].buttons = hand.previous;
    }
  }
  return in;
}

ActionList InteractionMachine::step(const InteractionInputs& inputs, ports::TimestampUs now_us) {
  ActionList out;
  const InteractionInputs in = effective(inputs);
  for (std::uint8_t h = 0; h < kHandCount; ++h) step_hand(h, in.hands[h], now_us, out);
  step_radius(in, out);
  for (std::uint8_t h = 0; h < kHandCount; ++h) hands_[h].previous = in.hands[h].buttons;
  return out;
}

void InteractionMachine::step_hand(std::uint8_t h, const HandInput& in, ports::TimestampUs now_us,
                                   ActionList& out) {
  Hand& hand = hands_[h];
  const HandStep step{h,
                      in,
                      in.buttons.grab && !hand.previous.grab,
                      in.buttons.move_object && !hand.previous.move_object,
                      in.buttons.freeze && !hand.previous.freeze,
                      now_us};
  switch (hand.state) {
    case HandState::idle:
      step_idle(step, out);
      break;
    case HandState::dragging:
      step_dragging(step, out);
      break;
    case HandState::dragging_lost:
      step_dragging_lost(step, out);
      break;
    case HandState::moving:
      step_moving(step, out);
      break;
    case HandState::moving_lost:
      step_moving_lost(step, out);
      break;
  }
  if (in.pose_valid) hand.last_valid_m = in.position_m;
}

bool InteractionMachine::lost_too_long(const HandStep& s) const {
  return s.now_us - hands_[s.hand].since_us >= config_.lost_timeout_us;
}

void InteractionMachine::step_idle(const HandStep& s, ActionList& out) {
  const std::uint8_t h = s.hand;
  if (s.grab_pressed) {
    if (!s.in.pose_valid) {
      out.push({ActionKind::refused, h, Reason::no_tracking, radius_m_});
    } else if (other_hand_grabs_near(h, s.in.position_m)) {
      out.push({ActionKind::refused, h, Reason::same_point, radius_m_});
    } else {
      enter(h, HandState::dragging, s.now_us);
      out.push({ActionKind::grab_begin, h, Reason::none, radius_m_});
    }
  } else if (s.move_pressed) {
    const HandState other = hands_[1 - h].state;
    if (!s.in.pose_valid) {
      out.push({ActionKind::refused, h, Reason::no_tracking, radius_m_});
    } else if (other == HandState::moving || other == HandState::moving_lost) {
      out.push({ActionKind::refused, h, Reason::object_busy, radius_m_});
    } else {
      enter(h, HandState::moving, s.now_us);
      out.push({ActionKind::move_begin, h, Reason::none, radius_m_});
    }
  }
}

void InteractionMachine::end_grab(const HandStep& s, ActionKind kind, Reason reason,
                                  ActionList& out) {
  enter(s.hand, HandState::idle, s.now_us);
  hands_[s.hand].disengaged = false;
  out.push({kind, s.hand, reason, radius_m_});
}

void InteractionMachine::step_dragging(const HandStep& s, ActionList& out) {
  const std::uint8_t h = s.hand;
  Hand& hand = hands_[h];
  if (!s.in.buttons.grab) {
    end_grab(s, ActionKind::commit, Reason::released, out);
  } else if (!s.in.pose_valid) {
    enter(h, HandState::dragging_lost, s.now_us);
    out.push({ActionKind::tracking_lost, h, Reason::none, radius_m_});
  } else if (hand.disengaged && !s.in.buttons.freeze) {
    hand.disengaged = false;
    out.push({ActionKind::unfreeze, h, Reason::none, radius_m_});
  } else if (s.freeze_pressed) {
    hand.disengaged = true;
    out.push({ActionKind::freeze, h, Reason::none, radius_m_});
  } else if (s.move_pressed) {
    out.push({ActionKind::refused, h, Reason::hand_busy, radius_m_});
  }
}

void InteractionMachine::step_dragging_lost(const HandStep& s, ActionList& out) {
  const std::uint8_t h = s.hand;
  Hand& hand = hands_[h];
  // Releasing while lost commits what the display shows: the warp held at the last
  // valid pose.
  if (!s.in.buttons.grab) {
    end_grab(s, ActionKind::commit, Reason::released, out);
  } else if (s.in.pose_valid) {
    enter(h, HandState::dragging, s.now_us);
    out.push({ActionKind::tracking_resumed, h, Reason::none, radius_m_});
  } else if (hand.disengaged && !s.in.buttons.freeze) {
    // Re-engaged at the last valid pose; the lost-tracking wait starts now.
    hand.disengaged = false;
    enter(h, HandState::dragging_lost, s.now_us);
    out.push({ActionKind::unfreeze, h, Reason::none, radius_m_});
  } else if ((!hand.disengaged || hand.buttons_gone) && lost_too_long(s)) {
    end_grab(s, ActionKind::cancel, Reason::tracking_timeout, out);
  }
}

void InteractionMachine::step_moving(const HandStep& s, ActionList& out) {
  const std::uint8_t h = s.hand;
  if (!s.in.buttons.move_object) {
    enter(h, HandState::idle, s.now_us);
    out.push({ActionKind::move_commit, h, Reason::released, radius_m_});
  } else if (!s.in.pose_valid) {
    enter(h, HandState::moving_lost, s.now_us);
    out.push({ActionKind::tracking_lost, h, Reason::none, radius_m_});
  } else if (s.grab_pressed) {
    out.push({ActionKind::refused, h, Reason::hand_busy, radius_m_});
  }
}

void InteractionMachine::step_moving_lost(const HandStep& s, ActionList& out) {
  const std::uint8_t h = s.hand;
  if (!s.in.buttons.move_object) {
    enter(h, HandState::idle, s.now_us);
    out.push({ActionKind::move_commit, h, Reason::released, radius_m_});
  } else if (s.in.pose_valid) {
    enter(h, HandState::moving, s.now_us);
    out.push({ActionKind::tracking_resumed, h, Reason::none, radius_m_});
  } else if (lost_too_long(s)) {
    enter(h, HandState::idle, s.now_us);
    out.push({ActionKind::move_cancel, h, Reason::tracking_timeout, radius_m_});
  }
}

void InteractionMachine::step_radius(const InteractionInputs& inputs, ActionList& out) {
  const HandInput& a = inputs.hands[0];
  const HandInput& b = inputs.hands[1];
  const bool both_held = config_.radius_gesture && a.buttons.radius && b.buttons.radius;
  // The radius is locked while a stroke or move is active: the stroke's weights
  // were computed with it.
  const bool both_idle = hands_[0].state == HandState::idle && hands_[1].state == HandState::idle;

  if (!both_held || !both_idle) {
    if (radius_ == RadiusGesture::active) {
      out.push({ActionKind::radius_end, 0, Reason::none, radius_m_});
    }
    radius_ = RadiusGesture::off;
    return;
  }
  if (!a.pose_valid || !b.pose_valid) return;  // hold the radius until tracking is back
  const float distance_m = glm::distance(a.position_m, b.position_m);
  switch (radius_) {
    case RadiusGesture::off:
      if (distance_m < config_.min_grab_separation_m) {
        radius_ = RadiusGesture::refused;
        out.push({ActionKind::refused, 0, Reason::hands_too_close, radius_m_});
      } else {
        radius_ = RadiusGesture::active;
        radius_start_m_ = radius_m_;
        radius_start_distance_m_ = distance_m;
        out.push({ActionKind::radius_begin, 0, Reason::none, radius_m_});
      }
      return;
    case RadiusGesture::active: {
      const float r = std::clamp(radius_start_m_ * distance_m / radius_start_distance_m_,
                                 config_.radius_min_m, config_.radius_max_m);
      if (r != radius_m_) {
        radius_m_ = r;
        out.push({ActionKind::radius_change, 0, Reason::none, radius_m_});
      }
      return;
    }
    case RadiusGesture::refused:
      return;  // wait until a radius button is released
  }
}

}  // namespace twister::input
