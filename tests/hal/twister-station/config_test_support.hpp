// Shared by the station config tests: every parse error, one per line, for
// substring checks and readable failures.
#pragma once

#include <string>

#include "config/station_config.hpp"

namespace twister::station_app::test {

// A station on a serial tracker with six GPIO button lines (the paper's three per
// hand), 11 lines long; the section under test is appended.
inline constexpr const char* kSixButtonStation = R"([station]
journal = "/tmp/j.bin"
mesh = "m.obj"
[tracker]
backend = "serial"
[tracker.serial]
device = "/dev/twister-fastrak"
[buttons]
backend = "gpiod"
[buttons.gpiod]
lines = [17, 27, 22, 23, 24, 25]
)";

inline std::string messages(const ConfigParseResult& r) {
  std::string s;
  for (const auto& e : r.errors) s += e.to_string() + "\n";
  return s;
}

}  // namespace twister::station_app::test
