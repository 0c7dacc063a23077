// MonotonicClock: the Clock port over CLOCK_MONOTONIC, in microseconds. The same
// clock the kernel uses for GPIO edge timestamps (libgpiod v1 reports them on
// CLOCK_MONOTONIC), so button edges and tracker samples share one time base.
#pragma once

#include "twister/ports/clock.hpp"

namespace twister::hal {

class MonotonicClock final : public ports::Clock {
 private:
  ports::TimestampUs do_now_us() override;
};

}  // namespace twister::hal
