// The [tracker.calibration] section of station.toml (documented key by key in
// hal/twister-station/deploy/station.toml and docs/hardware.md): hemisphere, boresight
// and its reference angles, the stylus tip offset, the unit's position and attitude
// filters, and [tracker.calibration.work_frame] (the transmitter-to-model transform:
// origin and axes in transmitter coordinates, metres). Private to the config library.
#pragma once

#include "config/station_config.hpp"
#include "config_reader.hpp"

namespace twister::station_app::internal {

// Reads [tracker.calibration] under the [tracker] reader `tracker`.
void read_calibration(ConfigReader& tracker, TrackerConfig& tc);

}  // namespace twister::station_app::internal
