// Clock port: monotonic time for the core. Tests drive a fake in virtual time.
#pragma once

#include <cstdint>

namespace twister::ports {

// Microseconds on a monotonic clock with an arbitrary epoch.
using TimestampUs = std::int64_t;

class Clock {
 public:
  virtual ~Clock() = default;
  // Never goes backwards. Thread-compatible; no errors.
  TimestampUs now_us() { return do_now_us(); }

 private:
  virtual TimestampUs do_now_us() = 0;
};

}  // namespace twister::ports
