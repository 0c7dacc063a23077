// Translation of the validated station.toml (hal::StationFileConfig) into the core's
// station::StationConfig: Fastrak protocol (enabled receivers, output lists incl.
// the stylus item when it is the button source), session timings, pose
// conversion, debounce, and the stylus-to-button-line binding. Init-time only.
#pragma once

#include "config/station_config.hpp"
#include "twister/hal/expected.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

// invalid_argument: the combination cannot run (the message says why).
hal::Expected<station::StationConfig> make_station_setup(const StationFileConfig& config);

}  // namespace twister::station_app
