#include "twister/station/station_event.hpp"

namespace twister::station {

const char* station_event_kind_name(StationEventKind kind) {
  switch (kind) {
    case StationEventKind::journal_recovered:
      return "journal_recovered";
    case StationEventKind::tracker_streaming:
      return "tracker_streaming";
    case StationEventKind::tracker_lost:
      return "tracker_lost";
    case StationEventKind::stroke_begin:
      return "stroke_begin";
    case StationEventKind::stroke_committed:
      return "stroke_committed";
    case StationEventKind::stroke_cancelled:
      return "stroke_cancelled";
    case StationEventKind::refused:
      return "refused";
    case StationEventKind::journal_error:
      return "journal_error";
    case StationEventKind::button_source_error:
      return "button_source_error";
    case StationEventKind::stroke_not_saved:
      return "stroke_not_saved";
    case StationEventKind::checkpoint_written:
      return "checkpoint_written";
    case StationEventKind::checkpoint_failed:
      return "checkpoint_failed";
    case StationEventKind::radius_set:
      return "radius_set";
    case StationEventKind::hand_disengaged:
      return "hand_disengaged";
    case StationEventKind::hand_engaged:
      return "hand_engaged";
    case StationEventKind::turn_limit_reached:
      return "turn_limit_reached";
    case StationEventKind::turn_limit_left:
      return "turn_limit_left";
    case StationEventKind::undone:
      return "undone";
    case StationEventKind::redone:
      return "redone";
    case StationEventKind::method_changed:
      return "method_changed";
    case StationEventKind::command_refused:
      return "command_refused";
    case StationEventKind::stroke_refined:
      return "stroke_refined";
    case StationEventKind::refinement_stopped:
      return "refinement_stopped";
  }
  return "unknown";
}

}  // namespace twister::station
