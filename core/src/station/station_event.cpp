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
  }
  return "unknown";
}

}  // namespace twister::station
