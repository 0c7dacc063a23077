// PacedLine: the simulated unit's output line at its baud rate: chunks queue behind each
// other, one byte per 10 bit times (8N1), each readable once transmitted. A LineQueue
// plus the time the line is free again. No heap.
//
// When a cycle's record may go (busy_at): the unit sends a station's record only when
// its slot finds the line free, and it counts the line as busy until one bit time after
// the last stop bit (its firmware sees the transmitter empty only then; assumed). Without
// that turnaround a record of exactly two cycles' length (VRPN's 32-byte binary list at
// 19,200 baud: 320 bit times = 1/60 s) would end exactly at the first station's next
// slot, which would always find the line free and the second station's never; a real
// unit reports both (issue 22, VRPN against twister-sim). Bytes are delivered at their
// transmission time, without the turnaround.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

#include "twister/sim/line_queue.hpp"

namespace twister::sim {

class PacedLine {
 public:
  // Queues `bytes` at `now`; returns how many did not fit (lost).
  std::size_t queue(std::span<const std::byte> bytes, ports::TimestampUs now, int baud) {
    const std::size_t n = std::min(bytes.size(), queue_.room());
    for (std::size_t i = 0; i < n; ++i) queue_.push(bytes[i]);
    const ports::TimestampUs start = std::max(now, free_at_);
    const auto duration =
        static_cast<ports::TimestampUs>(static_cast<double>(n) * 10.0 * 1e6 / baud);
    free_at_ = start + duration;
    quiet_at_ = free_at_ + static_cast<ports::TimestampUs>(1e6 / baud);
    queue_.end_chunk(free_at_);
    return bytes.size() - n;
  }
  // Empties the line; it is free from `now` on.
  void clear(ports::TimestampUs now) {
    queue_.clear();
    free_at_ = quiet_at_ = now;
  }
  // True while a record queued at `t` would find the line busy (turnaround included).
  bool busy_at(ports::TimestampUs t) const { return quiet_at_ > t; }
  LineQueue& queue() { return queue_; }
  const LineQueue& queue() const { return queue_; }

 private:
  LineQueue queue_;
  ports::TimestampUs free_at_ = 0;   // the last queued byte's stop bit is out
  ports::TimestampUs quiet_at_ = 0;  // ... and the unit has seen it (one bit time later)
};

}  // namespace twister::sim
