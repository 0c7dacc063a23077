// Helpers for the Liberty-family tests: hex byte strings, whole-stream parsing.
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

inline std::vector<FastrakEvent> parse_all(LibertyParser& parser, std::string_view stream,
                                           const std::vector<std::size_t>& chunks = {}) {
  std::vector<FastrakEvent> out;
  std::size_t pos = 0, k = 0;
  while (pos < stream.size()) {
    std::size_t n = chunks.empty() ? stream.size() : chunks[k++ % chunks.size()];
    if (n == 0) n = 1;
    n = std::min(n, stream.size() - pos);
    parser.feed(bytes_of(stream.substr(pos, n)), [&](const FastrakEvent& e) { out.push_back(e); });
    pos += n;
  }
  for (auto e = parser.finish(); e.ok(); e = parser.finish()) out.push_back(*e);
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
