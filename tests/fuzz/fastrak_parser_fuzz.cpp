// libFuzzer harness for FastrakParser. Byte 0 picks the configuration (format: bit 0
// binary, with bit 7 also set the 16-bit packed format; units, stylus width, one of
// several multi-station list sets), byte 1 the chunk size; the
// rest is the stream. Properties: no crash or out-of-bounds access; the same events
// for whole and chunked feeding; every pose passes the plausibility checks; all bytes
// are accounted for; pose conversion never fails on an emitted pose's shape.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace {

using namespace twister::tracker;

FastrakConfig config_from(std::uint8_t b) {
  FastrakConfig c;
  c.format = (b & 1) ? ((b & 0x80) ? Format::binary16 : Format::binary) : Format::ascii;
  c.units = (b & 2) ? Units::centimetres : Units::inches;
  c.ascii_stylus_width = (b & 4) ? 2 : 1;
  switch ((b >> 3) % 5) {
    case 0:
      c.stations[0] = {true, OutputList::of({Item::position, Item::euler, Item::crlf})};
      break;
    case 1:
      c.stations[0] = {
          true, OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::space})};
      c.stations[1] = {true, OutputList::of({Item::position, Item::quaternion, Item::space})};
      break;
    case 2:
      c.stations[0] = {true, OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z,
                                             Item::crlf})};
      c.stations[2] = {true,
                       OutputList::of({Item::position, Item::euler, Item::stylus, Item::crlf})};
      break;
    case 3:
      c.stations[0] = {true, OutputList::of({Item::position_ext, Item::euler_ext, Item::crlf})};
      c.stations[1] = {true, OutputList::of({Item::quaternion_ext, Item::space})};
      c.stations[3] = {true, OutputList::of({Item::position, Item::crlf})};
      break;
    default:
      for (auto& s : c.stations)
        s = {true, OutputList::of({Item::position, Item::quaternion, Item::crlf})};
      break;
  }
  return c;
}

struct Summary {
  std::uint64_t hash = 1469598103934665603ull;
  std::uint64_t events = 0;
  void add(std::uint64_t v) { hash = (hash ^ v) * 1099511628211ull; }
};

void check_pose(const FastrakPose& p, const FastrakConfig& c) {
  const float lim = c.units == Units::inches ? 400.0f : 1016.0f;
  for (float v : p.position) {
    if (!std::isfinite(v) || std::fabs(v) > lim) std::abort();
  }
  if (std::fabs(p.euler_deg[0]) > 180.0f || std::fabs(p.euler_deg[1]) > 90.0f ||
      std::fabs(p.euler_deg[2]) > 180.0f) {
    std::abort();
  }
  if (p.has.quaternion) {
    const double n = std::sqrt(
        double(p.quaternion[0]) * p.quaternion[0] + double(p.quaternion[1]) * p.quaternion[1] +
        double(p.quaternion[2]) * p.quaternion[2] + double(p.quaternion[3]) * p.quaternion[3]);
    if (!(std::fabs(n - 1.0) <= 0.0101)) std::abort();
  }
  PoseConversion conv;
  conv.units = c.units;
  conv.format = c.format;
  auto f = to_station_frame(p, conv);
  if (f.ok() && !(std::isfinite(f->origin.x) && std::isfinite(f->u.x))) std::abort();
}

Summary run(const FastrakConfig& c, std::span<const std::byte> in, std::size_t chunk) {
  FastrakParser parser(c);
  Summary s;
  auto sink = [&](const FastrakEvent& e) {
    ++s.events;
    s.add(static_cast<std::uint64_t>(e.kind));
    switch (e.kind) {
      case EventKind::pose:
        check_pose(e.pose, c);
        s.add(e.pose.station);
        s.add(static_cast<std::uint64_t>(std::fabs(e.pose.position[0]) * 100.0f));
        break;
      case EventKind::error:
        s.add(static_cast<std::uint64_t>(e.error));
        break;
      case EventKind::resync:
        s.add(e.dropped);
        break;
      case EventKind::status:
        s.add(e.status.flags);
        break;
      case EventKind::reply:
        s.add(e.reply.length);
        break;
    }
  };
  for (std::size_t pos = 0; pos < in.size(); pos += chunk) {
    parser.feed(in.subspan(pos, std::min(chunk, in.size() - pos)), sink);
  }
  for (auto e = parser.finish(); e.ok(); e = parser.finish()) sink(*e);
  if (parser.counters().bytes != in.size()) std::abort();
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const FastrakConfig c = config_from(data[0]);
  const std::size_t chunk = 1 + data[1] % 64;
  const auto in = std::as_bytes(std::span<const std::uint8_t>(data + 2, size - 2));
  const Summary whole = run(c, in, in.size() + 1);
  const Summary split = run(c, in, chunk);
  if (whole.hash != split.hash || whole.events != split.events) std::abort();
  return 0;
}
