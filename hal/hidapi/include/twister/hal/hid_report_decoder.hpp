// HidReportDecoder: turns successive HID input reports into button edges. Button i
// is pressed when (report[bits[i].byte] & bits[i].mask) != 0; a report shorter than
// a button's byte leaves that button unchanged. Pure logic (no I/O, no clock): the
// backend stamps the edges. Fixed capacity, allocation-free.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/ports/button_source.hpp"

namespace twister::hal {

struct HidButtonBitMap {
  std::uint8_t byte = 0;
  std::uint8_t mask = 0;
};

class HidReportDecoder {
 public:
  static constexpr std::size_t kMaxButtons = 8;

  // invalid_argument: more than kMaxButtons or a zero mask.
  Status configure(std::span<const HidButtonBitMap> bits);
  std::size_t button_count() const { return count_; }

  // Compares report with the previous levels and writes one edge per changed button
  // into out (line, pressed; time_us = now_us). Returns the number written.
  std::size_t decode(std::span<const std::uint8_t> report, ports::TimestampUs now_us,
                     std::span<ports::ButtonEdge, kMaxButtons> out);

 private:
  std::array<HidButtonBitMap, kMaxButtons> bits_{};
  std::array<bool, kMaxButtons> pressed_{};
  std::size_t count_ = 0;
};

}  // namespace twister::hal
