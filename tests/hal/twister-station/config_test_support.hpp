// Shared by the station config tests: every parse error, one per line, for
// substring checks and readable failures.
#pragma once

#include <string>

#include "config/station_config.hpp"

namespace twister::station_app::test {

inline std::string messages(const ConfigParseResult& r) {
  std::string s;
  for (const auto& e : r.errors) s += e.to_string() + "\n";
  return s;
}

}  // namespace twister::station_app::test
