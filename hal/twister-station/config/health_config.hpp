// The [health] section of station.toml (private to the config library): the fleet
// metrics file, its period, the archive's file system, systemd STATUS=.
#pragma once

#include "config/station_config.hpp"
#include "config_reader.hpp"

namespace twister::station_app::internal {

void read_health(ConfigReader& root, StationFileConfig& cfg);

}  // namespace twister::station_app::internal
