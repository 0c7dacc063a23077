// Translation of the validated station.toml (hal::StationConfig) into the core's
// station::StationConfig: Fastrak protocol (enabled receivers, output lists incl.
// the stylus item when it is the button source), session timings, pose
// conversion, debounce, and the stylus-to-button-line binding. Init-time only.
#pragma once

#include <string>

#include "config/station_config.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

struct StationSetup {
  station::StationConfig core{};
  std::string error;  // non-empty: the combination cannot run (message for the log)
  bool ok() const { return error.empty(); }
};

StationSetup make_station_setup(const StationConfig& config);

}  // namespace twister::station_app
