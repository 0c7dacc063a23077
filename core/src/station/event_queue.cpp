#include "twister/station/event_queue.hpp"

namespace twister::station {

bool EventQueue::push(const session::SessionEvent& event) {
  if (count_ == kCapacity) return false;
  items_[(head_ + count_) % kCapacity] = event;
  ++count_;
  return true;
}

Result<session::SessionEvent> EventQueue::pop() {
  if (count_ == 0) return StatusCode::unavailable;
  const session::SessionEvent e = items_[head_];
  head_ = (head_ + 1) % kCapacity;
  --count_;
  return e;
}

}  // namespace twister::station
