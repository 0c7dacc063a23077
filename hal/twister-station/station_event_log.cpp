#include "station_event_log.hpp"

#include "twister/input/interaction_machine.hpp"

namespace twister::station_app {

void log_station_event(hal::Logger& log, const station::StationEvent& e) {
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
      log.info("stroke", "hand %u cancelled (tracking lost too long); model unchanged [t=%.3f s]",
               e.hand, t);
      break;
    case K::refused:
      log.info("stroke", "press refused: hand %u (%s) [t=%.3f s]", e.hand,
               input::reason_name(static_cast<input::Reason>(e.value)), t);
      break;
    case K::journal_error:
      log.error("journal", "append failed (%s); stroke not recorded [t=%.3f s]", e.status.name(),
                t);
      break;
    case K::button_source_error:
      log.warning("buttons", "device failed (%s); reopening [t=%.3f s]", e.status.name(), t);
      break;
  }
}

}  // namespace twister::station_app
