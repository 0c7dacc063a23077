// EventQueue: the station's events on their way out: waiting for the log (oldest
// first, a fixed ring; what does not fit is dropped, push() says so and the station
// counts it), and the notices they mean for the display (NoticeBoard, posted by every
// push, whether the log's ring had room or not).
#pragma once

#include <cstddef>

#include "twister/base/inline_ring.hpp"
#include "twister/base/result.hpp"
#include "twister/session/session_events.hpp"
#include "twister/station/notice_board.hpp"

namespace twister::station {

class EventQueue {
 public:
  static constexpr std::size_t kCapacity = 64;

  // false: full, the event is dropped.
  bool push(const session::SessionEvent& event);
  // The oldest event. unavailable: none pending.
  Result<session::SessionEvent> pop();
  std::size_t size() const { return items_.size(); }
  const NoticeBoard& notices() const { return notices_; }

 private:
  InlineRing<session::SessionEvent, kCapacity> items_;
  NoticeBoard notices_;
};

}  // namespace twister::station
