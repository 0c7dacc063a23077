#include "twister/hal/hid_report_decoder.hpp"

namespace twister::hal {

Status HidReportDecoder::configure(std::span<const HidButtonBitMap> bits) {
  if (bits.size() > kMaxButtons) return StatusCode::invalid_argument;
  for (const auto& b : bits) {
    if (b.mask == 0) return StatusCode::invalid_argument;
  }
  count_ = bits.size();
  for (std::size_t i = 0; i < count_; ++i) bits_[i] = bits[i];
  pressed_.fill(false);
  return ok_status();
}

std::size_t HidReportDecoder::decode(std::span<const std::uint8_t> report,
                                     ports::TimestampUs now_us,
                                     std::span<ports::ButtonEdge, kMaxButtons> out) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    if (bits_[i].byte >= report.size()) continue;  // short report: no news for this button
    const bool pressed = (report[bits_[i].byte] & bits_[i].mask) != 0;
    if (pressed == pressed_[i]) continue;
    pressed_[i] = pressed;
    out[n++] = ports::ButtonEdge{static_cast<std::uint8_t>(i), pressed, now_us};
  }
  return n;
}

}  // namespace twister::hal
