// Fastrak wire facts (docs/fastrak-protocol.md §2-§3) and the protocol
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
// Control-byte commands (docs/fastrak-protocol.md §2).
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

// `F` / `f`. binary = IEEE-754 LE float32 (Fastrak); binary16 = the 16-bit packed
// format of the protocol family (Isotrak II / 3SPACE, docs/fastrak-protocol.md §3.4): 16-bit LE
// integers, sent in groups of 7 bytes with bit 7 stripped plus one byte of high bits, the record's
// first byte marked by bit 7 (sync).
enum class Format : std::uint8_t { ascii, binary, binary16 };
enum class Units : std::uint8_t { inches, centimetres };  // `U` / `u`

// 16-bit packed format (§3.4): the first wire byte of a record is '0' | 0x80; every
// other wire byte has bit 7 clear. Position counts span +-65.48 in (+-166.32 cm) over
// +-32768; angles +-180 degrees over +-32768 (assumed: 3SPACE convention); direction
// cosines and quaternion parts count / 32767.
inline constexpr std::uint8_t kPacked16Sync = 0x80;
inline constexpr unsigned kPacked16Start = 0x30u | kPacked16Sync;  // '0' with the sync bit
inline constexpr double kPacked16PositionFullScaleIn = 65.48;
inline constexpr double kPacked16PositionFullScaleCm = 166.32;
inline constexpr double kPacked16AngleFullScaleDeg = 180.0;
inline constexpr double kPacked16UnitCounts = 32767.0;

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

struct ReceiverConfig {
  bool enabled = false;
  OutputList list = OutputList::of({Item::position, Item::euler, Item::crlf});  // default 2,4,1
};

// What the parser needs to frame records (§3.8 "configuration").
struct FastrakConfig {
  Format format = Format::ascii;
  Units units = Units::inches;
  std::array<ReceiverConfig, kMaxStations> stations{};  // index = station number - 1
  // ASCII width of the stylus item 16: 1 or 2, unconfirmed (docs/fastrak-protocol.md §3.5).
  std::uint8_t ascii_stylus_width = 1;
};

// Bytes one item takes in `format` (binary16: logical bytes before packing); 0 for an
// unsupported code or an item the format cannot carry (extended items in binary16).
std::size_t item_width(Item item, Format format, std::uint8_t ascii_stylus_width = 1);

// Logical bytes of a data record (header included): what the items add up to.
std::size_t logical_record_length(const OutputList& list, Format format,
                                  std::uint8_t ascii_stylus_width = 1);
// Bytes of a whole data record on the wire (binary16: after packing, 8 per 7).
std::size_t record_length(const OutputList& list, Format format,
                          std::uint8_t ascii_stylus_width = 1);

// 16-bit packing (§3.4). Wire bytes for `logical` bytes: logical + ceil(logical / 7).
constexpr std::size_t packed16_length(std::size_t logical) { return logical + (logical + 6) / 7; }
// Logical bytes carried by `wire` packed bytes (the inverse of packed16_length).
constexpr std::size_t unpacked16_length(std::size_t wire) { return wire - (wire + 7) / 8; }
// Packs `logical` into `wire` (at least packed16_length bytes) and marks the first
// byte with the sync bit; returns the wire bytes written.
std::size_t pack16(const std::byte* logical, std::size_t n, std::byte* wire);
// Unpacks `wire_n` wire bytes into `logical` (unpacked16_length bytes). false: the
// first byte lacks the sync bit or another byte has bit 7 set (lost sync).
bool unpack16(const std::byte* wire, std::size_t wire_n, std::byte* logical);

// Orthonormality tolerance of a decoded orientation in `format` (docs/fastrak-protocol.md §3.8,
// §4): 0.01 for ASCII (4 decimals), 1e-3 for 16-bit counts, 1e-4 for IEEE floats.
double orthonormal_tolerance(Format format);

// Checks a configuration: every list non-empty, supported items only (binary16: no
// extended items), record <= 254 bytes, at least one station enabled, stylus width
// 1 or 2.
// invalid_argument: any of these fails.
Status validate(const FastrakConfig& config);

}  // namespace twister::tracker
