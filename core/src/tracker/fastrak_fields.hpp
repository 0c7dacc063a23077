// Private helpers shared by the parser and the encoder: fixed-width ASCII number
// fields (docs/fastrak-protocol.md §3.2). Binary float32 fields (§3.3) go through the byte cursor
// of twister/base/internal/byte_cursor.hpp.
#pragma once

#include <cstddef>
#include <cstdint>

#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker::internal {

inline char ch(std::byte b) { return static_cast<char>(b); }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// The number items of the output list (§2.1, §3.2): codes 50 and up are the
// extended 13-character form; the short ASCII form has 2 decimals for positions and
// Euler angles, 4 for direction cosines and quaternions.
inline bool is_extended(Item item) { return static_cast<std::uint8_t>(item) >= 50; }
inline int ascii_decimals(Item item) {
  return item == Item::position || item == Item::euler ? 2 : 4;
}
// Row of R (0, 1, 2) that a direction-cosine item carries.
inline std::size_t dcm_row(Item item) {
  const Item first = is_extended(item) ? Item::dcm_x_ext : Item::dcm_x;
  return static_cast<std::size_t>(item) - static_cast<std::size_t>(first);
}

// Parses a 7-character field with `decimals` decimals: `%7.2f` style ("  -3.21") or
// sign-column style ("-  3.21"); no other characters. False on any syntax error.
bool parse_fixed(const std::byte* p, std::size_t width, int decimals, float& out);
// Writes `value` as `%<width>.<decimals>f`, clamped to what the field can hold.
void write_fixed(std::byte* p, std::size_t width, int decimals, float value);

// 16-bit packed numbers (§3.4): value per count of a number item in `units`.
double packed16_scale(Item item, Units units);
// Reads / writes one little-endian 16-bit count as a value (writing rounds and clamps
// to the count range).
float read_packed16(const std::byte* p, double scale);
void write_packed16(std::byte* p, double scale, float value);

// Extended 13-character field `Sx.xxxxxESxxb` (§3.2).
bool parse_extended(const std::byte* p, float& out);
void write_extended(std::byte* p, float value);

}  // namespace twister::tracker::internal
