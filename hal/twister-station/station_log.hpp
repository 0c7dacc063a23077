// Log lines of twister-station: one line per event of the station's vocabulary
// (session::SessionEvent, the session's and the station's own), with its level and
// component (docs/hardware.md "While running"), formatted from the event's typed
// payload. Notices are what a technician or the sculptor's helper should see by
// default (tracker up, radius set, turn limit, undo, redo, method changes, refused
// commands); info is the stroke-by-stroke detail (grabs, commits, the clutch, moves,
// tracking of a hand, checkpoints written); debug the live radius of the gesture;
// warnings and errors are trouble (a stroke or undo that was not saved is an error:
// "stroke not saved: disk full"). The program passes its logger (hal::process_log());
// tests a recording sink. No allocation.
#pragma once

#include "twister/ports/log_sink.hpp"
#include "twister/session/session_events.hpp"

namespace twister::station_app {

// The level of an event's line.
ports::LogLevel station_event_level(const session::SessionEvent& event);

// The component an event's line names ("stroke", "journal", "tracker", ...).
const char* station_event_component(const session::SessionEvent& event);

// Writes the event's line to `log`. `storage_errno`: the journal file's last errno
// (0: unknown), to name the reason of a commit that was not saved ("disk full").
void log_station_event(const session::SessionEvent& event, ports::LogSink& log,
                       int storage_errno = 0);

// A short reason for a storage errno: "disk full" (ENOSPC), "file size limit
// reached" (EFBIG), "disk quota exceeded", else strerror's text; "i/o failure" for 0.
const char* storage_error_text(int storage_errno);

}  // namespace twister::station_app
