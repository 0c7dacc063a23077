// Item widths and configuration checks (spec §2.1, §3.2, §3.3).
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
      return bin ? 12 : 21;
    case Item::quaternion:
      return bin ? 16 : 28;
    case Item::stylus:
    case Item::stylus_ext:
      return bin ? 2 : ascii_stylus_width;
    case Item::position_ext:
    case Item::euler_ext:
    case Item::dcm_x_ext:
    case Item::dcm_y_ext:
    case Item::dcm_z_ext:
      return bin ? 12 : 39;
    case Item::quaternion_ext:
      return bin ? 16 : 52;
  }
  return 0;
}

std::size_t record_length(const OutputList& list, Format format, std::uint8_t ascii_stylus_width) {
  std::size_t n = kHeaderBytes;
  for (std::size_t i = 0; i < list.count && i < kMaxItems; ++i) {
    n += item_width(list.items[i], format, ascii_stylus_width);
  }
  return n;
}

Status validate(const FastrakConfig& config) {
  if (config.ascii_stylus_width != 1 && config.ascii_stylus_width != 2) {
    return StatusCode::invalid_argument;
  }
  bool any = false;
  for (const StationConfig& st : config.stations) {
    if (!st.enabled) continue;
    any = true;
    if (st.list.count == 0 || st.list.count > kMaxItems) return StatusCode::invalid_argument;
    for (std::size_t i = 0; i < st.list.count; ++i) {
      if (!is_supported_item(static_cast<std::uint8_t>(st.list.items[i]))) {
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
