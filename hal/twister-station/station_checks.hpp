// Checks twister-station makes before it touches anything (with --check and before
// every start, so a wrong option or a missing file ends the program with exit code 2
// before the journal is opened or replayed).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "config/station_config.hpp"

namespace twister::station_app {

// The files the config names that are not there or not usable: station.mesh
// (relative to the config's folder; a regular file), tracker.sim.scenario_file (when
// the simulator plays one; a regular file), the journal's folder (the journal itself
// may be new; if it exists it must be a regular file). One message per problem,
// "KEY: PATH: what is wrong".
std::vector<std::string> referenced_file_problems(const StationFileConfig& config,
                                                  const std::filesystem::path& config_dir);

// "" when `address` has the form --link takes (as [link] address: unix:PATH,
// tcp:A.B.C.D:PORT or serial:DEVICE), else what is wrong. A syntax check only:
// nothing is opened or bound.
std::string link_address_problem(const std::string& address);

}  // namespace twister::station_app
