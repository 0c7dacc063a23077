// Log lines of twister-station: one line per StationEvent, with its level and
// component (docs/hardware.md "While running"). Notices are what a technician or the
// sculptor's helper should see by default (tracker up, radius set, turn limit, undo,
// redo, method changes, refused commands); info is the stroke-by-stroke detail
// (grabs, commits, the clutch); warnings and errors are trouble. The program passes
// its logger (hal::process_log()); tests a recording sink. No allocation.
#pragma once

#include "twister/ports/log_sink.hpp"
#include "twister/station/station_event.hpp"

namespace twister::station_app {

// The level of an event's line.
ports::LogLevel station_event_level(const station::StationEvent& event);

// Writes the event's line to `log`.
void log_station_event(const station::StationEvent& event, ports::LogSink& log);

}  // namespace twister::station_app
