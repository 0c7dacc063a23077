// HidapiButtonSource: the ButtonSource port over a USB HID device (buttons, foot
// pedal) via hidapi's hidraw backend. Opened by hidraw path, or by vendor/product id
// (first match). Reads are non-blocking; edges are stamped with the injected clock
// when the report is read (HID reports carry no timestamp), so their time resolution
// is the event loop's period. hidapi offers no fd, so as a PollSource it asks for
// none (the event loop polls it every loop_timeout_ms); reopen() opens the device
// again with the config of the last open().
// Errors: open() -> unavailable (no such device), io_error (open failed: permissions),
// invalid_argument (bad button map); poll() -> unavailable (no edge), io_error
// (device unplugged: it is closed, connected() false, until reopen() finds it again),
// failed_precondition (not open).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "twister/base/inline_ring.hpp"
#include "twister/hal/hid_report_decoder.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"

struct hid_device_;

namespace twister::hal {

struct HidapiButtonConfig {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string path;                      // wins over the ids when not empty
  std::vector<HidButtonBitMap> buttons;  // button i = buttons[i]
};

class HidapiButtonSource final : public ports::ButtonSource, public PollSource {
 public:
  explicit HidapiButtonSource(ports::Clock& clock) : clock_(clock) {}
  ~HidapiButtonSource() override;
  HidapiButtonSource(const HidapiButtonSource&) = delete;
  HidapiButtonSource& operator=(const HidapiButtonSource&) = delete;

  Status open(const HidapiButtonConfig& config);
  void close();

 private:
  Result<ports::ButtonEdge> do_poll() override;
  std::uint8_t do_line_count() const override {
    return static_cast<std::uint8_t>(decoder_.button_count());
  }
  bool do_connected() const override { return device_ != nullptr; }
  std::size_t do_poll_fds(std::span<pollfd>) const override { return 0; }
  Status do_reopen() override;
  ports::ButtonEdge take_pending();

  ports::Clock& clock_;
  hid_device_* device_ = nullptr;
  HidReportDecoder decoder_;
  // Edges of the last report not handed out yet, oldest first.
  InlineRing<ports::ButtonEdge, HidReportDecoder::kMaxButtons> pending_;
  std::array<std::uint8_t, 64> report_{};
  HidapiButtonConfig config_;  // of the last open(), for reopen()
  bool configured_ = false;
};

}  // namespace twister::hal
