// EventQueue: the station's events waiting for the log (oldest first), a fixed ring.
// What does not fit is dropped (push() says so; the station counts it).
#pragma once

#include <array>
#include <cstddef>

#include "twister/base/result.hpp"
#include "twister/session/session_events.hpp"

namespace twister::station {

class EventQueue {
 public:
  static constexpr std::size_t kCapacity = 64;

  // false: full, the event is dropped.
  bool push(const session::SessionEvent& event);
  // The oldest event. unavailable: none pending.
  Result<session::SessionEvent> pop();
  std::size_t size() const { return count_; }

 private:
  std::array<session::SessionEvent, kCapacity> items_{};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace twister::station
