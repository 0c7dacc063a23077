// Readiness waits for real-time tests: block in poll(2) on what a backend asks the
// station's loop to wait on, instead of sleeping and retrying.
#pragma once

#include <poll.h>

#include <array>
#include <chrono>

#include "twister/hal/poll_source.hpp"

namespace twister::test {

// Waits until one of `source`'s descriptors is ready (input, hang-up, error) or
// `timeout_ms` passes. true: something is ready; false: timeout, or the source
// offers no descriptor now.
inline bool wait_ready(const hal::PollSource& source, int timeout_ms) {
  std::array<pollfd, hal::PollSource::kMaxFds> fds{};
  const std::size_t n = source.poll_fds(fds);
  if (n == 0) return false;
  return ::poll(fds.data(), n, timeout_ms) > 0;
}

// Milliseconds left until `deadline` (0 once it passed).
inline int ms_until(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
  return left.count() > 0 ? static_cast<int>(left.count()) : 0;
}

}  // namespace twister::test
