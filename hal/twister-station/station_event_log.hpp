// The station's events as log lines of twister-station, each at its level:
// tracker lost and failed buttons are warnings, a stroke that was not saved an error,
// tracker streaming and the journal's recovery notices, every stroke event
// (grab, commit, cancel, refused press) info. Lines read "stroke: hand 0 committed
// as journal record 3 [t=12.345 s]" (t: the station clock). No heap.
#pragma once

#include "twister/hal/logger.hpp"
#include "twister/station/station_event.hpp"

namespace twister::station_app {

// `storage_errno`: the journal file's last errno (0: unknown), to name the reason
// of a stroke that was not saved ("disk full").
void log_station_event(hal::Logger& log, const station::StationEvent& event, int storage_errno = 0);

// A short reason for a storage errno: "disk full" (ENOSPC), "file size limit
// reached" (EFBIG), "disk quota exceeded", else strerror's text; "i/o failure" for 0.
const char* storage_error_text(int storage_errno);

}  // namespace twister::station_app
