// Encoder: the exact inverse of the parser's framing, so the device model and the
// round-trip tests share one definition of the wire layout.
#include "twister/tracker/fastrak_encoder.hpp"

#include <array>

#include "fastrak_fields.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::tracker {
namespace {

// Writes the `n` numbers of a number item (the inverse of the parser's read).
void put_numbers(std::byte* p, const FastrakConfig& config, Item item, const float* v,
                 std::size_t n) {
  const Format format = config.format;
  if (format == Format::binary16) {
    const double scale = internal::packed16_scale(item, config.units);
    for (std::size_t i = 0; i < n; ++i) internal::write_packed16(p + 2 * i, scale, v[i]);
    return;
  }
  if (format == Format::binary) {
    twister::internal::ByteWriter w({p, 4 * n});
    for (std::size_t i = 0; i < n; ++i) w.f32(v[i]);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (internal::is_extended(item)) {
      internal::write_extended(p + 13 * i, v[i]);
    } else {
      internal::write_fixed(p + 7 * i, 7, internal::ascii_decimals(item), v[i]);
    }
  }
}

}  // namespace

Result<std::size_t> encode_record(const FastrakPose& pose, const FastrakConfig& config,
                                  std::span<std::byte> out) {
  if (!validate(config).ok() || pose.station < 1 || pose.station > kMaxStations) {
    return StatusCode::invalid_argument;
  }
  const ReceiverConfig& st = config.stations[pose.station - 1u];
  if (!st.enabled) return StatusCode::invalid_argument;
  const Format fmt = config.format;
  const std::size_t len = record_length(st.list, fmt, config.ascii_stylus_width);
  if (out.size() < len) return StatusCode::resource_exhausted;
  // binary16: the logical record is built here and packed into `out` at the end.
  std::array<std::byte, kMaxRecordBytes> logical{};
  std::byte* p = fmt == Format::binary16 ? logical.data() : out.data();
  p[0] = static_cast<std::byte>(kRecordType);
  p[1] = static_cast<std::byte>('0' + pose.station);
  p[2] = static_cast<std::byte>(pose.status);
  std::size_t off = kHeaderBytes;
  for (std::size_t i = 0; i < st.list.count; ++i) {
    const Item item = st.list.items[i];
    std::byte* q = p + off;
    switch (item) {
      case Item::space:
        q[0] = static_cast<std::byte>(' ');
        break;
      case Item::crlf:
        q[0] = static_cast<std::byte>(kCr);
        q[1] = static_cast<std::byte>(kLf);
        break;
      case Item::position:
      case Item::position_ext:
        put_numbers(q, config, item, pose.position.data(), 3);
        break;
      case Item::euler:
      case Item::euler_ext:
        put_numbers(q, config, item, pose.euler_deg.data(), 3);
        break;
      case Item::dcm_x:
      case Item::dcm_y:
      case Item::dcm_z:
      case Item::dcm_x_ext:
      case Item::dcm_y_ext:
      case Item::dcm_z_ext:
        put_numbers(q, config, item, pose.dcm.data() + 3 * internal::dcm_row(item), 3);
        break;
      case Item::quaternion:
      case Item::quaternion_ext:
        put_numbers(q, config, item, pose.quaternion.data(), 4);
        break;
      case Item::stylus:
      case Item::stylus_ext: {
        const std::size_t w = fmt == Format::ascii ? config.ascii_stylus_width : 2;
        if (w == 2) q[0] = static_cast<std::byte>(' ');
        q[w - 1] = static_cast<std::byte>(pose.button ? '1' : '0');
        break;
      }
    }
    off += item_width(item, fmt, config.ascii_stylus_width);
  }
  if (fmt == Format::binary16) return pack16(logical.data(), off, out.data());
  return len;
}

Result<std::size_t> encode_status(const FastrakStatus& status, std::span<std::byte> out) {
  if (out.size() < kStatusReplyBytes) return StatusCode::resource_exhausted;
  static constexpr char kHex[] = "0123456789ABCDEF";
  // Bytes 1-based per docs/fastrak-protocol.md §3.6: '2', station, 'S', 3 hex flags,
  // 3-char BIT code, blank, ID tag, sensor map, blanks, 6-char firmware, 32-char system
  // id, CR LF.
  char text[kStatusReplyBytes + 1] = "21S3F0    013    3.00Twister simulated FASTRAK       \r\n";
  text[1] =
      static_cast<char>('0' + (status.station >= 1 && status.station <= 4 ? status.station : 1));
  std::uint16_t flags = status.flags;
  flags =
      static_cast<std::uint16_t>((flags & ~0xBu) | (status.binary ? 1u : 0u) |
                                 (status.centimetres ? 2u : 0u) | (status.continuous ? 8u : 0u));
  text[3] = kHex[(flags >> 8) & 0xF];
  text[4] = kHex[(flags >> 4) & 0xF];
  text[5] = kHex[flags & 0xF];
  for (std::size_t i = 0; i < kStatusReplyBytes; ++i) out[i] = static_cast<std::byte>(text[i]);
  return kStatusReplyBytes;
}

}  // namespace twister::tracker
