// Liberty-family frame encoder: the exact inverse of LibertyParser's framing.
#include "twister/tracker/liberty_encoder.hpp"

#include <bit>

namespace twister::tracker {
namespace {

void put_u32(std::byte* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::byte>((v >> (8 * i)) & 0xFFu);
}

void put_floats(std::byte* p, const float* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) put_u32(p + 4 * i, std::bit_cast<std::uint32_t>(v[i]));
}

}  // namespace

Result<std::size_t> encode_liberty_frame(const FastrakPose& pose, const LibertyConfig& config,
                                         std::span<std::byte> out,
                                         const LibertyFrameExtras& extras) {
  if (!validate(config).ok() || pose.station < 1 || pose.station > kLibertyMaxStations) {
    return StatusCode::invalid_argument;
  }
  const LibertyStationConfig& st = config.stations[pose.station - 1u];
  if (!st.enabled) return StatusCode::invalid_argument;
  const std::size_t body = liberty_body_length(st.list);
  const std::size_t len = kLibertyHeaderBytes + body;
  if (out.size() < len) return StatusCode::resource_exhausted;
  const auto tag = frame_tag(config.model);
  const std::size_t size = liberty_size_value(body, config.size_field);
  std::byte* p = out.data();
  p[0] = static_cast<std::byte>(tag[0]);
  p[1] = static_cast<std::byte>(tag[1]);
  p[2] = static_cast<std::byte>(pose.station);
  p[3] = static_cast<std::byte>(extras.command);
  p[4] = static_cast<std::byte>(pose.status == ' ' ? 0 : pose.status);
  p[5] = std::byte{0};
  p[6] = static_cast<std::byte>(size & 0xFFu);
  p[7] = static_cast<std::byte>((size >> 8) & 0xFFu);
  std::byte* q = p + kLibertyHeaderBytes;
  for (std::size_t i = 0; i < st.list.count; ++i) {
    const LibertyItem item = st.list.items[i];
    switch (item) {
      case LibertyItem::space:
        q[0] = static_cast<std::byte>(' ');
        break;
      case LibertyItem::crlf:
        q[0] = static_cast<std::byte>(kCr);
        q[1] = static_cast<std::byte>(kLf);
        break;
      case LibertyItem::position:
      case LibertyItem::position_ext:
        put_floats(q, pose.position.data(), 3);
        break;
      case LibertyItem::euler:
      case LibertyItem::euler_ext:
        put_floats(q, pose.euler_deg.data(), 3);
        break;
      case LibertyItem::dcm:
        put_floats(q, pose.dcm.data(), 9);
        break;
      case LibertyItem::quaternion:
        put_floats(q, pose.quaternion.data(), 4);
        break;
      case LibertyItem::timestamp:
        put_u32(q, extras.timestamp);
        break;
      case LibertyItem::frame_count:
        put_u32(q, extras.frame_count);
        break;
      case LibertyItem::stylus:
        put_u32(q, pose.button ? 1u : 0u);
        break;
      case LibertyItem::distortion:
        put_u32(q, static_cast<std::uint32_t>(extras.distortion));
        break;
    }
    q += liberty_item_width(item);
  }
  return len;
}

}  // namespace twister::tracker
