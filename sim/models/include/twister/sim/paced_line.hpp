// PacedLine: the simulated unit's output line at its baud rate: chunks queue behind each
// other, one byte per 10 bit times (8N1), each readable once transmitted. A LineQueue
// plus the time the line is free again. No heap.
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
    queue_.end_chunk(free_at_);
    return bytes.size() - n;
  }
  // Empties the line; it is free from `now` on.
  void clear(ports::TimestampUs now) {
    queue_.clear();
    free_at_ = now;
  }
  bool busy_at(ports::TimestampUs t) const { return free_at_ > t; }
  LineQueue& queue() { return queue_; }
  const LineQueue& queue() const { return queue_; }

 private:
  LineQueue queue_;
  ports::TimestampUs free_at_ = 0;
};

}  // namespace twister::sim
