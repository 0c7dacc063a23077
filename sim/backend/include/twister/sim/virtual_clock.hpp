// VirtualClock: a Clock the event loop advances itself (simulator runs in virtual
// time: deterministic, as fast as the CPU allows). Microseconds, starts at start_us.
#pragma once

#include "twister/ports/clock.hpp"

namespace twister::sim {

class VirtualClock final : public ports::Clock {
 public:
  explicit VirtualClock(ports::TimestampUs start_us = 0) : now_us_(start_us) {}
  void advance_us(ports::TimestampUs delta_us) { now_us_ += delta_us; }

 private:
  ports::TimestampUs do_now_us() override { return now_us_; }
  ports::TimestampUs now_us_;
};

}  // namespace twister::sim
