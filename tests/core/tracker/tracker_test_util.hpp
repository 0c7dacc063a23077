// Helpers for the tracker tests: byte strings, whole-stream parsing, common configs.
// Sections (§N) are those of docs/fastrak-protocol.md.
#pragma once

#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "twister/tracker/fastrak_parser.hpp"

namespace twister::tracker::test {

inline std::span<const std::byte> bytes_of(std::string_view s) {
  return std::as_bytes(std::span<const char>(s.data(), s.size()));
}

inline std::string f32le(float f) {
  std::string s(4, '\0');
  std::uint32_t v;
  std::memcpy(&v, &f, 4);
  for (int i = 0; i < 4; ++i)
    s[static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFF);
  return s;
}

// The default output list (position, Euler angles, CR LF) and the manual's own
// record for it: "01 " + x y z + az el roll + CR LF, 47 bytes (§3.2).
inline const OutputList kDefaultList = OutputList::of({Item::position, Item::euler, Item::crlf});
inline const std::string kDefaultAscii = std::string("01 ") + "  12.50" + "  -3.21" + "-123.45" +
                                         "  90.00" + "   0.00" + " 180.00" + "\r\n";

// Feeds `stream` in chunks of the given sizes (cycled; empty = all at once), then
// finish(); returns every event. Any parser with feed() and finish() (Fastrak, Liberty).
template <typename Parser>
std::vector<FastrakEvent> parse_all(Parser& parser, std::string_view stream,
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

inline FastrakConfig one_station(Format format, OutputList list, Units units = Units::inches) {
  FastrakConfig c;
  c.format = format;
  c.units = units;
  c.stations[0].enabled = true;
  c.stations[0].list = list;
  return c;
}

}  // namespace twister::tracker::test
