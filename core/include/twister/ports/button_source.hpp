// ButtonSource port: raw (not debounced) level changes of button lines, each with
// the time the hardware saw it. Debouncing happens in core/input. A device that can
// be missing or unplugged (a GPIO chip, a USB HID device) says so: connected() is
// false from the poll() that reported it gone (or from start-up, when it was not
// there) until it is opened again; the station then runs without it.
#pragma once

#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/ports/clock.hpp"

namespace twister::ports {

struct ButtonEdge {
  std::uint8_t line = 0;    // index into the source's configured lines, 0-based
  bool pressed = false;     // logical level after active-low handling
  TimestampUs time_us = 0;  // when the edge happened (kernel timestamp if available)
};

class ButtonSource {
 public:
  virtual ~ButtonSource() = default;

  // Next pending edge. unavailable: none pending. io_error: the device is gone
  // (connected() is false from then on). failed_precondition: not connected.
  Result<ButtonEdge> poll() { return do_poll(); }

  // The device is there and open. Sources that cannot vanish keep the default.
  bool connected() const { return do_connected(); }

  // Number of configured lines (edges carry line < line_count()).
  std::uint8_t line_count() const { return do_line_count(); }

 private:
  virtual Result<ButtonEdge> do_poll() = 0;
  virtual std::uint8_t do_line_count() const = 0;
  virtual bool do_connected() const { return true; }
};

}  // namespace twister::ports
