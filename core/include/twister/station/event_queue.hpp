// EventQueue: the station's events waiting for the log (oldest first), a fixed ring.
// What does not fit is dropped (push() says so; the station counts it).
#pragma once

#include <cstddef>

#include "twister/base/inline_ring.hpp"
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
  std::size_t size() const { return items_.size(); }

 private:
  InlineRing<session::SessionEvent, kCapacity> items_;
};

}  // namespace twister::station
