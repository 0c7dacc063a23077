#include "twister/session/session_events.hpp"

namespace twister::session {

const char* session_event_kind_name(SessionEventKind kind) {
  switch (kind) {
    case SessionEventKind::grab_begin:
      return "grab_begin";
    case SessionEventKind::committed:
      return "committed";
    case SessionEventKind::cancelled:
      return "cancelled";
    case SessionEventKind::tracking_lost:
      return "tracking_lost";
    case SessionEventKind::tracking_resumed:
      return "tracking_resumed";
    case SessionEventKind::refused:
      return "refused";
    case SessionEventKind::radius_changed:
      return "radius_changed";
    case SessionEventKind::move_begin:
      return "move_begin";
    case SessionEventKind::move_committed:
      return "move_committed";
    case SessionEventKind::move_cancelled:
      return "move_cancelled";
    case SessionEventKind::undone:
      return "undone";
    case SessionEventKind::redone:
      return "redone";
    case SessionEventKind::not_saved:
      return "not_saved";
    case SessionEventKind::history_overflow:
      return "history_overflow";
    case SessionEventKind::radius_set:
      return "radius_set";
    case SessionEventKind::disengaged:
      return "disengaged";
    case SessionEventKind::engaged:
      return "engaged";
    case SessionEventKind::turn_limit_reached:
      return "turn_limit_reached";
    case SessionEventKind::turn_limit_left:
      return "turn_limit_left";
    case SessionEventKind::method_changed:
      return "method_changed";
    case SessionEventKind::command_refused:
      return "command_refused";
    case SessionEventKind::refined:
      return "refined";
    case SessionEventKind::refine_stopped:
      return "refine_stopped";
  }
  return "unknown";
}

void SessionEvents::push(const SessionEvent& event) {
  if (count_ == items_.size()) {
    ++dropped_;
    return;
  }
  items_[count_++] = event;
}

}  // namespace twister::session
