#include "twister/hal/monotonic_clock.hpp"

#include <time.h>

namespace twister::hal {

ports::TimestampUs MonotonicClock::do_now_us() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);  // cannot fail for CLOCK_MONOTONIC
  return static_cast<ports::TimestampUs>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1'000;
}

}  // namespace twister::hal
