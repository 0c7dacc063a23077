#include "station_event_log.hpp"

#include <cerrno>
#include <cstring>

#include "twister/input/interaction_machine.hpp"

namespace twister::station_app {

const char* storage_error_text(int storage_errno) {
  switch (storage_errno) {
    case 0:
      return "i/o failure";
    case ENOSPC:
      return "disk full";
    case EFBIG:
      return "file size limit reached";
    case EDQUOT:
      return "disk quota exceeded";
    default:
      return std::strerror(storage_errno);
  }
}

void log_station_event(hal::Logger& log, const station::StationEvent& e, int storage_errno) {
  using K = station::StationEventKind;
  const double t = static_cast<double>(e.time_us) / 1e6;
  switch (e.kind) {
    case K::journal_recovered:
      if (e.value == 0) {
        log.notice("journal", "%u good records [t=%.3f s]", e.sequence, t);
      } else {
        log.notice("journal", "%u good records, cut a torn tail of %llu bytes [t=%.3f s]",
                   e.sequence, static_cast<unsigned long long>(e.value), t);
      }
      break;
    case K::checkpoint_written:
      log.info("journal", "checkpoint of %u records written (%llu bytes) [t=%.3f s]", e.sequence,
               static_cast<unsigned long long>(e.value), t);
      break;
    case K::checkpoint_failed:
      log.warning("journal", "checkpoint not written (%s); the previous one stays [t=%.3f s]",
                  e.status.name(), t);
      break;
    case K::tracker_streaming:
      log.notice("tracker", "streaming (start-up #%llu) [t=%.3f s]",
                 static_cast<unsigned long long>(e.value), t);
      break;
    case K::tracker_lost:
      log.warning("tracker",
                  "lost (unplugged, silent or garbled); waiting and re-initialising [t=%.3f s]", t);
      break;
    case K::stroke_begin:
      log.info("stroke", "hand %u grabbed [t=%.3f s]", e.hand, t);
      break;
    case K::stroke_committed:
      log.info("stroke", "hand %u committed as journal record %u [t=%.3f s]", e.hand, e.sequence,
               t);
      break;
    case K::stroke_cancelled:
      if (static_cast<input::Reason>(e.value) == input::Reason::none) {
        log.notice("stroke", "hand %u cancelled (station stopping); model unchanged [t=%.3f s]",
                   e.hand, t);
      } else {
        log.info("stroke", "hand %u cancelled (tracking lost too long); model unchanged [t=%.3f s]",
                 e.hand, t);
      }
      break;
    case K::refused:
      log.info("stroke", "press refused: hand %u (%s) [t=%.3f s]", e.hand,
               input::reason_name(static_cast<input::Reason>(e.value)), t);
      break;
    case K::journal_error:
      log.error("journal", "%s (%s) [t=%.3f s]", e.status.name(), storage_error_text(storage_errno),
                t);
      break;
    case K::stroke_not_saved:
      log.error("stroke",
                "hand %u: stroke not saved: %s (%s); the model is back at the last saved "
                "stroke [t=%.3f s]",
                e.hand,
                e.status.code() == StatusCode::io_error ? storage_error_text(storage_errno)
                                                        : "the warp could not be applied",
                e.status.name(), t);
      break;
    case K::button_source_error:
      log.warning("buttons", "device failed (%s); reopening [t=%.3f s]", e.status.name(), t);
      break;
  }
}

}  // namespace twister::station_app
