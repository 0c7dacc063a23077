// The [sculpt] section of station.toml (documented key by key in
// hal/twister-station/deploy/station.toml and docs/hardware.md): warp method, radius
// and its gesture, turn tracking and limit, lost-tracking timeout, and the button map
// by name per hand ([sculpt.buttons.left] / [sculpt.buttons.right]: a line or a chord
// per action), checked against the button backend's lines. Private to the config
// library; read after [buttons], whose line count it needs.
#pragma once

#include "config/station_config.hpp"
#include "config_reader.hpp"

namespace twister::station_app::internal {

void read_sculpt(ConfigReader& root, StationFileConfig& cfg);

}  // namespace twister::station_app::internal
