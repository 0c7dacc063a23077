#include "twister/hal/hid_report_decoder.hpp"

namespace twister::hal {

Status HidReportDecoder::configure(std::span<const HidButtonBitMap> bits) {
  if (bits.size() > kMaxButtons) return StatusCode::invalid_argument;
  for (const auto& b : bits) {
    if (b.mask == 0) return StatusCode::invalid_argument;
  }
  bits_.assign(bits).ignore();  // fits: checked above
  pressed_.fill(false);
  return ok_status();
}

HidReportDecoder::Edges HidReportDecoder::decode(std::span<const std::uint8_t> report,
                                                 ports::TimestampUs now_us) {
  Edges out;
  for (std::size_t i = 0; i < bits_.size(); ++i) {
    if (bits_[i].byte >= report.size()) continue;  // short report: no news for this button
    const bool pressed = (report[bits_[i].byte] & bits_[i].mask) != 0;
    if (pressed == pressed_[i]) continue;
    pressed_[i] = pressed;
    // One per button at most: cannot be full.
    out.push_back(ports::ButtonEdge{static_cast<std::uint8_t>(i), pressed, now_us}).ignore();
  }
  return out;
}

}  // namespace twister::hal
