// HidReportDecoder: turns successive HID input reports into button edges. Button i
// is pressed when (report[bits[i].byte] & bits[i].mask) != 0; a report shorter than
// a button's byte leaves that button unchanged. Pure logic (no I/O, no clock): the
// backend stamps the edges. Fixed capacity, allocation-free.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/ports/button_source.hpp"

namespace twister::hal {

struct HidButtonBitMap {
  std::uint8_t byte = 0;
  std::uint8_t mask = 0;
};

class HidReportDecoder {
 public:
  static constexpr std::size_t kMaxButtons = 8;
  using Edges = InlineVector<ports::ButtonEdge, kMaxButtons>;

  // invalid_argument: more than kMaxButtons or a zero mask.
  Status configure(std::span<const HidButtonBitMap> bits);
  std::size_t button_count() const { return bits_.size(); }

  // Compares report with the previous levels: one edge per changed button (line,
  // pressed; time_us = now_us), lowest line first.
  Edges decode(std::span<const std::uint8_t> report, ports::TimestampUs now_us);

 private:
  InlineVector<HidButtonBitMap, kMaxButtons> bits_;
  std::array<bool, kMaxButtons> pressed_{};  // per button of bits_
};

}  // namespace twister::hal
