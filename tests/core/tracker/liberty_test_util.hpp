// Helpers for the Liberty-family tests: hex byte strings (parse_all is
// tracker_test_util.hpp's, for any parser).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tracker_test_util.hpp"
#include "twister/tracker/liberty_parser.hpp"

namespace twister::tracker::test {

// "4C 59 01" -> the three bytes; spaces and '|' are separators.
inline std::string hex(std::string_view s) {
  std::string out;
  int hi = -1;
  for (char c : s) {
    int v = -1;
    if (c >= '0' && c <= '9') v = c - '0';
    if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
    if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
    if (v < 0) continue;
    if (hi < 0) {
      hi = v;
    } else {
      out.push_back(static_cast<char>(hi * 16 + v));
      hi = -1;
    }
  }
  return out;
}


inline LibertyConfig liberty_one_station(LibertyModel model, LibertyOutputList list,
                                         int station = 1) {
  LibertyConfig c;
  c.model = model;
  c.stations[static_cast<std::size_t>(station - 1)].enabled = true;
  c.stations[static_cast<std::size_t>(station - 1)].list = list;
  return c;
}

}  // namespace twister::tracker::test
