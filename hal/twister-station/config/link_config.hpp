// The [link] section of station.toml (private to the config library).
#pragma once

#include <string>

#include "config/station_config.hpp"
#include "config_reader.hpp"

namespace twister::station_app::internal {

// Reads and checks [link]: every key's type and range, the address form, and the
// rules across keys (a non-loopback TCP address needs listen = "network", which
// needs psk_file).
void read_link(ConfigReader& root, StationFileConfig& cfg);

// "" unless `link` is a TCP address without psk_file and without
// allow_unauthenticated_tcp; then what is wrong and how to fix it.
std::string unauthenticated_tcp_problem(const LinkSection& link);

// The address form alone: "" when `address` is unix:PATH, tcp:A.B.C.D:PORT or
// serial:DEVICE, else what is wrong. `loopback` tells whether a tcp: host is on
// 127.0.0.0/8 (true for the other kinds).
std::string check_link_address(const std::string& address, bool& loopback);

}  // namespace twister::station_app::internal
