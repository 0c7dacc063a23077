#include "twister/session/session_events.hpp"

namespace twister::session {
namespace {

template <class P>
constexpr std::size_t index_of() {
  return EventPayload(P{}).index();
}

}  // namespace

const char* session_event_kind_name(SessionEventKind kind) {
  using K = SessionEventKind;
  switch (kind) {
    case K::grab_begin:
      return "grab_begin";
    case K::committed:
      return "committed";
    case K::cancelled:
      return "cancelled";
    case K::tracking_lost:
      return "tracking_lost";
    case K::tracking_resumed:
      return "tracking_resumed";
    case K::refused:
      return "refused";
    case K::radius_changed:
      return "radius_changed";
    case K::move_begin:
      return "move_begin";
    case K::move_committed:
      return "move_committed";
    case K::move_cancelled:
      return "move_cancelled";
    case K::undone:
      return "undone";
    case K::redone:
      return "redone";
    case K::not_saved:
      return "not_saved";
    case K::history_overflow:
      return "history_overflow";
    case K::radius_set:
      return "radius_set";
    case K::disengaged:
      return "disengaged";
    case K::engaged:
      return "engaged";
    case K::turn_limit_reached:
      return "turn_limit_reached";
    case K::turn_limit_left:
      return "turn_limit_left";
    case K::method_changed:
      return "method_changed";
    case K::symmetry_changed:
      return "symmetry_changed";
    case K::command_refused:
      return "command_refused";
    case K::refined:
      return "refined";
    case K::refine_stopped:
      return "refine_stopped";
    case K::journal_recovered:
      return "journal_recovered";
    case K::tracker_streaming:
      return "tracker_streaming";
    case K::tracker_lost:
      return "tracker_lost";
    case K::buttons_lost:
      return "buttons_lost";
    case K::buttons_found:
      return "buttons_found";
    case K::checkpoint_written:
      return "checkpoint_written";
    case K::checkpoint_failed:
      return "checkpoint_failed";
    case K::visitor:
      return "visitor";
  }
  return "unknown";
}

std::size_t payload_index(SessionEventKind kind) {
  using K = SessionEventKind;
  switch (kind) {
    case K::committed:
    case K::cancelled:
    case K::not_saved:
      return index_of<payload::StrokeEnd>();
    case K::refused:
    case K::move_cancelled:
      return index_of<payload::Reasoned>();
    case K::radius_changed:
    case K::radius_set:
      return index_of<payload::Radius>();
    case K::move_committed:
    case K::undone:
    case K::redone:
    case K::history_overflow:
    case K::disengaged:
      return index_of<payload::RecordRef>();
    case K::turn_limit_reached:
    case K::turn_limit_left:
      return index_of<payload::TurnLimit>();
    case K::method_changed:
      return index_of<payload::Method>();
    case K::symmetry_changed:
      return index_of<payload::Symmetry>();
    case K::command_refused:
      return index_of<payload::CommandRefusal>();
    case K::refined:
      return index_of<payload::Refinement>();
    case K::refine_stopped:
      return index_of<payload::RefinementStop>();
    case K::journal_recovered:
      return index_of<payload::JournalRecovered>();
    case K::checkpoint_written:
      return index_of<payload::CheckpointWritten>();
    case K::tracker_streaming:
      return index_of<payload::TrackerStreaming>();
    case K::visitor:
      return index_of<payload::Visitor>();
    case K::grab_begin:
    case K::tracking_lost:
    case K::tracking_resumed:
    case K::move_begin:
    case K::engaged:
    case K::tracker_lost:
    case K::buttons_lost:
    case K::buttons_found:
    case K::checkpoint_failed:
      break;
  }
  return index_of<std::monostate>();
}

SessionEvent make_event(SessionEventKind kind, std::uint8_t hand, EventPayload payload,
                        Status status) {
  TWISTER_ASSERT(payload.index() == payload_index(kind));
  SessionEvent e;
  e.kind = kind;
  e.hand = hand;
  e.status = status;
  e.payload = payload;
  return e;
}

void SessionEvents::push(const SessionEvent& event) {
  if (!items_.push_back(event).ok()) ++dropped_;
}

}  // namespace twister::session
