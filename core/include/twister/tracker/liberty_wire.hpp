// Liberty / Patriot / Latus binary frame facts (docs/liberty-protocol.md) and the
// configuration the parser and encoder share. Unlike a Fastrak record a frame carries its
// own size, but the parser still checks it against the station's output list, so a frame
// is accepted only when header, size and list agree.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include "twister/base/result.hpp"
#include "twister/base/status.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

// Frame header (docs/liberty-protocol.md §2): tag (2 bytes), station (binary, 1-based),
// initiating command, error byte, reserved byte, little-endian 16-bit size.
inline constexpr std::size_t kLibertyHeaderBytes = 8;
inline constexpr std::size_t kLibertySizeOffset = 6;
// Stations a frame may name (the Liberty 240/16 has 16 sensors; the Patriot 2).
inline constexpr int kLibertyMaxStations = 16;
inline constexpr std::size_t kLibertyMaxItems = 32;
// The longest body accepted. A frame announcing more is rejected without buffering it
// (never allocate or wait for what a peer announces). 240 holds position, Euler,
// direction cosines, quaternion, timestamp, frame count, stylus, distortion and CR LF
// (94 bytes) twice over.
inline constexpr std::size_t kLibertyMaxBodyBytes = 240;
inline constexpr std::size_t kLibertyMaxFrameBytes = kLibertyHeaderBytes + kLibertyMaxBodyBytes;
// Command bytes of data frames: continuous output and a single poll.
inline constexpr char kLibertyContinuous = 'C';
inline constexpr char kLibertyPoll = 'P';

enum class LibertyModel : std::uint8_t { liberty, patriot, latus };
// The two tag characters of a model's frames: "LY", "PA", "LU".
std::array<char, 2> frame_tag(LibertyModel model);
const char* liberty_model_name(LibertyModel model);

// Output-list item codes of the Liberty family (`O` command; docs/liberty-protocol.md
// §3). In binary every number is a little-endian IEEE float or a 32-bit integer.
enum class LibertyItem : std::uint8_t {
  space = 0,         // 1 byte ' '
  crlf = 1,          // 2 bytes CR LF
  position = 2,      // 3 floats x, y, z
  position_ext = 3,  // 3 floats (extended precision is the same in binary)
  euler = 4,         // 3 floats azimuth, elevation, roll (degrees)
  euler_ext = 5,     // 3 floats
  dcm = 6,           // 9 floats, rows X, Y, Z (as the Fastrak's items 5, 6, 7)
  quaternion = 7,    // 4 floats w, x, y, z
  timestamp = 8,     // uint32 (read, not reported)
  frame_count = 9,   // uint32 (read, not reported)
  stylus = 10,       // uint32: nonzero = switch closed
  distortion = 11,   // int32 (read, not reported)
};
bool is_supported_liberty_item(std::uint8_t code);
// Bytes one item takes in a binary frame; 0 for an unsupported code.
std::size_t liberty_item_width(LibertyItem item);

struct LibertyOutputList {
  std::array<LibertyItem, kLibertyMaxItems> items{};
  std::uint8_t count = 0;

  static constexpr LibertyOutputList of(std::initializer_list<LibertyItem> list) {
    LibertyOutputList out;
    for (LibertyItem i : list) out.items[out.count++] = i;
    return out;
  }
};

// Body bytes (after the header) the items add up to.
std::size_t liberty_body_length(const LibertyOutputList& list);

// The list the station asks a Liberty for, mirroring its Fastrak list item for item:
// position, orientation (Euler, direction cosines or quaternion), stylus, CR LF, space.
// invalid_argument: a Fastrak item without a Liberty equivalent.
Status to_liberty_list(const OutputList& fastrak, LibertyOutputList& out);

// The inverse for the items a Fastrak list can say: direction cosines become the three
// rows, every other item its Fastrak counterpart (extended precision as plain).
// invalid_argument: timestamp, frame count or distortion (no Fastrak item), or too long.
Status to_fastrak_list(const LibertyOutputList& liberty, OutputList& out);

// The `O` command setting a station's list in the family's own item codes (§3):
// "O<station>,<code>,...\r". Returns the bytes written.
// invalid_argument: station outside 1..kLibertyMaxStations or an empty list;
// out_of_range: `out` is too small.
Result<std::size_t> encode_liberty_output_list(int station, const LibertyOutputList& list,
                                               std::span<char> out);

struct LibertyStationConfig {
  bool enabled = false;
  LibertyOutputList list = LibertyOutputList::of(
      {LibertyItem::position, LibertyItem::euler, LibertyItem::crlf});  // default 2,4,1
};

// What the size field counts. The SDK's readers take it as the bytes after the header
// (body); the alternative (whole frame, header included) is kept selectable because the
// public sources leave it open (docs/liberty-protocol.md §2).
enum class LibertySizeField : std::uint8_t { body, frame };

struct LibertyConfig {
  LibertyModel model = LibertyModel::liberty;
  Units units = Units::inches;
  LibertySizeField size_field = LibertySizeField::body;
  std::array<LibertyStationConfig, kLibertyMaxStations> stations{};  // index = station - 1
};

// The size field a frame of `body` body bytes carries under `config`.
std::size_t liberty_size_value(std::size_t body, LibertySizeField field);

// The configuration that frames what a Liberty-family unit of `model` sends for a
// Fastrak configuration: the same stations, units and lists (to_liberty_list).
// invalid_argument: a list does not translate.
Status to_liberty_config(const FastrakConfig& fastrak, LibertyModel model, LibertyConfig& out);

// Every enabled list non-empty with supported items and a body <= kLibertyMaxBodyBytes;
// at least one station enabled.
// invalid_argument: any of these fails.
Status validate(const LibertyConfig& config);

}  // namespace twister::tracker
