// FakeClock: virtual time for core tests (never sleeps).
#pragma once

#include "twister/ports/clock.hpp"

namespace twister::test {

class FakeClock final : public ports::Clock {
 public:
  explicit FakeClock(ports::TimestampUs start_us = 0) : now_us_(start_us) {}
  void advance_us(ports::TimestampUs delta_us) { now_us_ += delta_us; }

 private:
  ports::TimestampUs do_now_us() override { return now_us_; }
  ports::TimestampUs now_us_;
};

}  // namespace twister::test
