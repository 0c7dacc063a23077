// Private helpers shared by the parser and the encoder: fixed-width ASCII number
// fields (spec §3.2) and little-endian float32 (§3.3).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

namespace twister::tracker::internal {

inline char ch(std::byte b) { return static_cast<char>(b); }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

inline float read_f32_le(const std::byte* p) {
  const std::uint32_t v =
      static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
      (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
  return std::bit_cast<float>(v);
}

inline void write_f32_le(std::byte* p, float f) {
  const auto v = std::bit_cast<std::uint32_t>(f);
  p[0] = static_cast<std::byte>(v & 0xFFu);
  p[1] = static_cast<std::byte>((v >> 8) & 0xFFu);
  p[2] = static_cast<std::byte>((v >> 16) & 0xFFu);
  p[3] = static_cast<std::byte>((v >> 24) & 0xFFu);
}

// Parses a 7-character field with `decimals` decimals: `%7.2f` style ("  -3.21") or
// sign-column style ("-  3.21"); no other characters. False on any syntax error.
bool parse_fixed(const std::byte* p, std::size_t width, int decimals, float& out);
// Writes `value` as `%<width>.<decimals>f`, clamped to what the field can hold.
void write_fixed(std::byte* p, std::size_t width, int decimals, float value);

// Extended 13-character field `Sx.xxxxxESxxb` (§3.2).
bool parse_extended(const std::byte* p, float& out);
void write_extended(std::byte* p, float value);

}  // namespace twister::tracker::internal
