// Shared body of the Liberty-family parser harnesses (one per model: liberty_parser_fuzz,
// patriot_parser_fuzz). Byte 0 picks the configuration (units, size convention, one of
// several multi-station list sets), byte 1 the chunk size; the rest is the stream.
// Properties: no crash or out-of-bounds access; the same events for whole and chunked
// feeding; every pose passes the plausibility checks and names an enabled station; all bytes
// are accounted for; oversize rejections are bad frames.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "twister/tracker/liberty_parser.hpp"

namespace twister::tracker::fuzz {

inline LibertyConfig liberty_config_from(LibertyModel model, std::uint8_t b) {
  using L = LibertyItem;
  LibertyConfig c;
  c.model = model;
  c.units = (b & 1) ? Units::centimetres : Units::inches;
  c.size_field = (b & 2) ? LibertySizeField::frame : LibertySizeField::body;
  switch ((b >> 2) % 5) {
    case 0:
      c.stations[0] = {true, LibertyOutputList::of({L::position, L::euler, L::crlf})};
      break;
    case 1:  // the station's lists
      c.stations[0] = {true,
                       LibertyOutputList::of({L::position, L::quaternion, L::stylus, L::crlf})};
      c.stations[1] = {true, LibertyOutputList::of({L::position, L::quaternion, L::crlf})};
      break;
    case 2:  // VRPN's list
      c.stations[0] = {true, LibertyOutputList::of(
                                 {L::position, L::quaternion, L::timestamp, L::stylus, L::space})};
      c.stations[3] = {true, LibertyOutputList::of({L::position, L::dcm, L::crlf})};
      break;
    case 3:  // the ROS driver's list
      c.stations[0] = {true, LibertyOutputList::of({L::timestamp, L::frame_count, L::distortion,
                                                    L::position_ext, L::quaternion})};
      c.stations[15] = {true, LibertyOutputList::of({L::euler_ext, L::space})};
      break;
    default:
      for (std::size_t i = 0; i < 8; ++i) {
        c.stations[i] = {true, LibertyOutputList::of({L::position, L::quaternion, L::space})};
      }
      break;
  }
  return c;
}

struct Summary {
  std::uint64_t hash = 1469598103934665603ull;
  std::uint64_t events = 0;
  void add(std::uint64_t v) { hash = (hash ^ v) * 1099511628211ull; }
};

inline void check_pose(const FastrakPose& p, const LibertyConfig& c) {
  if (p.station < 1 || p.station > kLibertyMaxStations || !c.stations[p.station - 1u].enabled) {
    std::abort();
  }
  const float lim = c.units == Units::inches ? 400.0f : 1016.0f;
  for (float v : p.position) {
    if (!std::isfinite(v) || std::fabs(v) > lim) std::abort();
  }
  if (std::fabs(p.euler_deg[0]) > 180.0f || std::fabs(p.euler_deg[1]) > 90.0f ||
      std::fabs(p.euler_deg[2]) > 180.0f) {
    std::abort();
  }
  if (p.has.quaternion) {
    double n = 0.0;
    for (float q : p.quaternion) n += double(q) * double(q);
    if (!(std::fabs(std::sqrt(n) - 1.0) <= 0.0011)) std::abort();
  }
}

inline Summary run(const LibertyConfig& c, std::span<const std::byte> in, std::size_t chunk) {
  LibertyParser parser(c);
  Summary s;
  std::uint64_t accepted = 0;
  auto sink = [&](const FastrakEvent& e) {
    ++s.events;
    s.add(static_cast<std::uint64_t>(e.kind));
    switch (e.kind) {
      case EventKind::pose:
        check_pose(e.pose, c);
        accepted += kLibertyHeaderBytes + liberty_body_length(c.stations[e.pose.station - 1u].list);
        s.add(e.pose.station);
        s.add(static_cast<std::uint64_t>(std::fabs(e.pose.position[0]) * 100.0f));
        break;
      case EventKind::error:
        accepted += kLibertyHeaderBytes + liberty_body_length(c.stations[e.station - 1u].list);
        s.add(static_cast<std::uint64_t>(e.error));
        break;
      case EventKind::resync:
        s.add(e.dropped);
        break;
      case EventKind::status:
      case EventKind::reply:
        std::abort();  // the Liberty parser reports neither
    }
  };
  for (std::size_t pos = 0; pos < in.size(); pos += chunk) {
    parser.feed(in.subspan(pos, std::min(chunk, in.size() - pos)), sink);
  }
  for (auto e = parser.finish(); e.ok(); e = parser.finish()) sink(*e);
  const LibertyParserCounters& k = parser.counters();
  if (k.bytes != in.size() || k.dropped_bytes + accepted != in.size()) std::abort();
  if (k.oversize > k.bad_frames) std::abort();
  s.add(k.bad_frames);
  return s;
}

inline int fuzz_one(LibertyModel model, const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const LibertyConfig c = liberty_config_from(model, data[0]);
  const std::size_t chunk = 1 + data[1] % 64;
  const auto in = std::as_bytes(std::span<const std::uint8_t>(data + 2, size - 2));
  const Summary whole = run(c, in, in.size() + 1);
  const Summary split = run(c, in, chunk);
  if (whole.hash != split.hash || whole.events != split.events) std::abort();
  return 0;
}

}  // namespace twister::tracker::fuzz
