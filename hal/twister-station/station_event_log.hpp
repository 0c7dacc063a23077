// The station's events as log lines of twister-station, each at its level:
// tracker lost and failed buttons are warnings, a failed journal append an error,
// tracker streaming and the journal's recovery notices, every stroke event
// (grab, commit, cancel, refused press) info. Lines read "stroke: hand 0 committed
// as journal record 3 [t=12.345 s]" (t: the station clock). No heap.
#pragma once

#include "twister/hal/logger.hpp"
#include "twister/station/station_event.hpp"

namespace twister::station_app {

void log_station_event(hal::Logger& log, const station::StationEvent& event);

}  // namespace twister::station_app
