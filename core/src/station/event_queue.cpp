#include "twister/station/event_queue.hpp"

namespace twister::station {

bool EventQueue::push(const session::SessionEvent& event) {
  notices_.see(event);
  return items_.push(event).ok();
}

Result<session::SessionEvent> EventQueue::pop() {
  if (items_.empty()) return StatusCode::unavailable;
  const session::SessionEvent e = items_.front();
  items_.pop_front();
  return e;
}

}  // namespace twister::station
