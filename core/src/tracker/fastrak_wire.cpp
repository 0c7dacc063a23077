// Item widths and configuration checks (docs/fastrak-protocol.md §2.1, §3.2, §3.3).
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

bool is_supported_item(std::uint8_t code) {
  switch (code) {
    case 0:
    case 1:
    case 2:
    case 4:
    case 5:
    case 6:
    case 7:
    case 11:
    case 16:
    case 52:
    case 54:
    case 55:
    case 56:
    case 57:
    case 61:
    case 66:
      return true;
    default:
      return false;
  }
}

std::size_t item_width(Item item, Format format, std::uint8_t ascii_stylus_width) {
  const bool bin = format == Format::binary;
  const bool b16 = format == Format::binary16;
  switch (item) {
    case Item::space:
      return 1;
    case Item::crlf:
      return 2;
    case Item::position:
    case Item::euler:
    case Item::dcm_x:
    case Item::dcm_y:
    case Item::dcm_z:
      return b16 ? 6 : bin ? 12 : 21;
    case Item::quaternion:
      return b16 ? 8 : bin ? 16 : 28;
    case Item::stylus:
      return bin || b16 ? 2 : ascii_stylus_width;
    case Item::stylus_ext:
      return b16 ? 0 : bin ? 2 : ascii_stylus_width;
    case Item::position_ext:
    case Item::euler_ext:
    case Item::dcm_x_ext:
    case Item::dcm_y_ext:
    case Item::dcm_z_ext:
      return b16 ? 0 : bin ? 12 : 39;
    case Item::quaternion_ext:
      return b16 ? 0 : bin ? 16 : 52;
  }
  return 0;
}

std::size_t logical_record_length(const OutputList& list, Format format,
                                  std::uint8_t ascii_stylus_width) {
  std::size_t n = kHeaderBytes;
  for (std::size_t i = 0; i < list.count && i < kMaxItems; ++i) {
    n += item_width(list.items[i], format, ascii_stylus_width);
  }
  return n;
}

std::size_t record_length(const OutputList& list, Format format, std::uint8_t ascii_stylus_width) {
  const std::size_t n = logical_record_length(list, format, ascii_stylus_width);
  return format == Format::binary16 ? packed16_length(n) : n;
}

std::size_t pack16(const std::byte* logical, std::size_t n, std::byte* wire) {
  std::size_t w = 0;
  for (std::size_t g = 0; g < n; g += 7) {
    const std::size_t k = n - g < 7 ? n - g : 7;
    unsigned high = 0;
    for (std::size_t i = 0; i < k; ++i) {
      const auto b = static_cast<unsigned>(logical[g + i]);
      high |= ((b >> 7) & 1u) << i;
      wire[w++] = static_cast<std::byte>(b & 0x7Fu);
    }
    wire[w++] = static_cast<std::byte>(high);
  }
  if (w > 0) wire[0] |= static_cast<std::byte>(kPacked16Sync);
  return w;
}

bool unpack16(const std::byte* wire, std::size_t wire_n, std::byte* logical) {
  if (wire_n == 0 || (static_cast<unsigned>(wire[0]) & kPacked16Sync) == 0) return false;
  for (std::size_t i = 1; i < wire_n; ++i) {
    if ((static_cast<unsigned>(wire[i]) & kPacked16Sync) != 0) return false;
  }
  const std::size_t n = unpacked16_length(wire_n);
  std::size_t w = 0;
  for (std::size_t g = 0; g < n; g += 7) {
    const std::size_t k = n - g < 7 ? n - g : 7;
    const auto high = static_cast<unsigned>(wire[w + k]);
    for (std::size_t i = 0; i < k; ++i) {
      const unsigned low = static_cast<unsigned>(wire[w + i]) & 0x7Fu;
      logical[g + i] = static_cast<std::byte>(low | (((high >> i) & 1u) << 7));
    }
    w += k + 1;
  }
  return true;
}

double orthonormal_tolerance(Format format) {
  switch (format) {
    case Format::ascii:
      return 0.01;
    case Format::binary16:
      return 1e-3;
    case Format::binary:
      break;
  }
  return 1e-4;
}

Status validate(const FastrakConfig& config) {
  if (config.ascii_stylus_width != 1 && config.ascii_stylus_width != 2) {
    return StatusCode::invalid_argument;
  }
  bool any = false;
  for (const ReceiverConfig& st : config.stations) {
    if (!st.enabled) continue;
    any = true;
    if (st.list.count == 0 || st.list.count > kMaxItems) return StatusCode::invalid_argument;
    for (std::size_t i = 0; i < st.list.count; ++i) {
      const Item item = st.list.items[i];
      if (!is_supported_item(static_cast<std::uint8_t>(item)) ||
          item_width(item, config.format, config.ascii_stylus_width) == 0) {
        return StatusCode::invalid_argument;
      }
    }
    // The parser frames by length only: a record must fit the pending buffer.
    if (record_length(st.list, config.format, config.ascii_stylus_width) > kMaxRecordBytes) {
      return StatusCode::invalid_argument;
    }
  }
  return any ? ok_status() : Status(StatusCode::invalid_argument);
}

}  // namespace twister::tracker
