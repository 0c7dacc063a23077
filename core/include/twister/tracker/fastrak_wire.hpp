// Fastrak wire facts (spec: shared/spec/fastrak-protocol.md §2-§3) and the protocol
// configuration the parser and encoder share: format, units and each station's output
// list. Records carry no length, so (station, list, format) fully determines a record.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>

#include "twister/base/status.hpp"

namespace twister::tracker {

inline constexpr char kRecordType = '0';  // data record, byte 0
inline constexpr char kReplyType = '2';   // replies (status, read-backs, errors)
inline constexpr char kCr = '\r';
inline constexpr char kLf = '\n';
// Control-byte commands (spec §2).
inline constexpr char kCtrlY = 0x19;            // re-initialise as at power-up
inline constexpr char kCtrlK = 0x0B;            // save the configuration to EEPROM
inline constexpr char kCtrlS = 0x13;            // suspend output (XOFF)
inline constexpr char kCtrlQ = 0x11;            // resume output (XON)
inline constexpr std::size_t kHeaderBytes = 3;  // '0', station digit, status char
inline constexpr int kMaxStations = 4;
inline constexpr std::size_t kMaxItems = 32;          // `O` accepts up to 32 items
inline constexpr std::size_t kMaxRecordBytes = 254;   // manual: record <= 254 bytes
inline constexpr std::size_t kStatusReplyBytes = 55;  // §3.6
inline constexpr std::size_t kMaxReplyBytes = 128;    // longest '2'-led line we accept

// Output-list item codes (§2.1) this implementation supports.
enum class Item : std::uint8_t {
  space = 0,
  crlf = 1,
  position = 2,
  euler = 4,
  dcm_x = 5,  // first row of R: X components of the receiver's x, y, z axes
  dcm_y = 6,
  dcm_z = 7,
  quaternion = 11,
  stylus = 16,
  position_ext = 52,
  euler_ext = 54,
  dcm_x_ext = 55,
  dcm_y_ext = 56,
  dcm_z_ext = 57,
  quaternion_ext = 61,
  stylus_ext = 66,
};

// True for the codes listed in Item.
bool is_supported_item(std::uint8_t code);

enum class Format : std::uint8_t { ascii, binary };       // `F` / `f` (binary = IEEE LE float32)
enum class Units : std::uint8_t { inches, centimetres };  // `U` / `u`

// One station's output list as sent with `O`s,i1,...,in.
struct OutputList {
  std::array<Item, kMaxItems> items{};
  std::uint8_t count = 0;

  static constexpr OutputList of(std::initializer_list<Item> list) {
    OutputList out;
    for (Item i : list) out.items[out.count++] = i;
    return out;
  }
};

struct StationConfig {
  bool enabled = false;
  OutputList list = OutputList::of({Item::position, Item::euler, Item::crlf});  // default 2,4,1
};

// What the parser needs to frame records (§3.8 "configuration").
struct FastrakConfig {
  Format format = Format::ascii;
  Units units = Units::inches;
  std::array<StationConfig, kMaxStations> stations{};  // index = station number - 1
  // ASCII width of the stylus item 16: the spec leaves 1 or 2 unconfirmed (§3.5).
  std::uint8_t ascii_stylus_width = 1;
};

// Bytes one item takes on the wire in `format`; 0 for an unsupported code.
std::size_t item_width(Item item, Format format, std::uint8_t ascii_stylus_width = 1);

// Bytes of a whole data record (header included) for one station's list.
std::size_t record_length(const OutputList& list, Format format,
                          std::uint8_t ascii_stylus_width = 1);

// Checks a configuration: every list non-empty, supported items only, record <= 254
// bytes, at least one station enabled, stylus width 1 or 2.
// invalid_argument: any of these fails.
Status validate(const FastrakConfig& config);

}  // namespace twister::tracker
