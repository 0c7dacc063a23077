#include "twister/hal/monotonic_clock.hpp"

#include <gtest/gtest.h>
#include <time.h>

namespace twister::hal {
namespace {

TEST(MonotonicClockTest, NeverGoesBackwardsAndAdvancesWithSleep) {
  MonotonicClock clock;
  ports::Clock& port = clock;
  const auto t0 = port.now_us();
  ports::TimestampUs prev = t0;
  for (int i = 0; i < 1000; ++i) {
    const auto t = port.now_us();
    ASSERT_GE(t, prev);
    prev = t;
  }
  timespec ts{0, 5'000'000};
  ::nanosleep(&ts, nullptr);
  const auto dt = port.now_us() - t0;
  EXPECT_GE(dt, 5'000);
  EXPECT_LT(dt, 5'000'000);  // generous: a loaded 2-core machine
}

TEST(MonotonicClockTest, MatchesClockMonotonicInMicroseconds) {
  MonotonicClock clock;
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  const auto ref = static_cast<ports::TimestampUs>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
  const auto t = clock.now_us();
  EXPECT_GE(t, ref);
  EXPECT_LT(t - ref, 1'000'000);
}

}  // namespace
}  // namespace twister::hal
