// DeviceReport: what a backend that searches for its device (libusb) found, as one
// line for the log: which device was found where, or what was looked for and not
// found, or why a device there cannot be used. The station's loop logs the line
// once each time it changes (changes() counts them), so a search repeated every
// back-off says nothing new until the answer differs. Never blocks or allocates.
#pragma once

#include <cstdint>

namespace twister::hal {

class DeviceReport {
 public:
  enum class Level : std::uint8_t { info, warning, error };

  virtual ~DeviceReport() = default;
  // Increases by one whenever text() or level() changes; 0 before the first search.
  virtual std::uint32_t changes() const = 0;
  virtual const char* text() const = 0;  // the current finding ("" before the first search)
  virtual Level level() const = 0;
};

}  // namespace twister::hal
