// [exhibit]: exhibit mode (issue 25): the visitor lifecycle, the new-sculpture chord,
// the archive directory and its retention budget (docs/hardware.md "[exhibit]").
#pragma once

#include "config/station_config.hpp"
#include "config_reader.hpp"

namespace twister::station_app::internal {

void read_exhibit(ConfigReader& root, StationFileConfig& cfg);

}  // namespace twister::station_app::internal
