// Log lines of twister-station: one line per StationEvent, with its level and
// component (docs/hardware.md "While running"). Notices are what a technician or the
// sculptor's helper should see by default (tracker up, radius set, turn limit, undo,
// redo, method changes, refused commands); info is the stroke-by-stroke detail
// (grabs, commits, the clutch, checkpoints written); warnings and errors are trouble
// (a stroke or undo that was not saved is an error: "stroke not saved: disk full").
// The program passes its logger (hal::process_log()); tests a recording sink. No
// allocation.
#pragma once

#include "twister/ports/log_sink.hpp"
#include "twister/station/station_event.hpp"

namespace twister::station_app {

// The level of an event's line.
ports::LogLevel station_event_level(const station::StationEvent& event);

// Writes the event's line to `log`. `storage_errno`: the journal file's last errno
// (0: unknown), to name the reason of a commit that was not saved ("disk full").
void log_station_event(const station::StationEvent& event, ports::LogSink& log,
                       int storage_errno = 0);

// A short reason for a storage errno: "disk full" (ENOSPC), "file size limit
// reached" (EFBIG), "disk quota exceeded", else strerror's text; "i/o failure" for 0.
const char* storage_error_text(int storage_errno);

}  // namespace twister::station_app
