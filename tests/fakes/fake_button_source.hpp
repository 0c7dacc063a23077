// FakeButtonSource: scripted raw button edges for core tests (fixed capacity, no
// allocation), plus a switch that makes the source fail like an unplugged device: its
// next poll() is io_error and it is not connected() until fail(false) (reopened), or
// set_connected(false) for one that is not there at all (at start-up).
#pragma once

#include <array>
#include <cstddef>

#include "twister/ports/button_source.hpp"

namespace twister::test {

template <std::size_t kCapacity = 256>
class FakeButtonSourceWithStorage final : public ports::ButtonSource {
 public:
  explicit FakeButtonSourceWithStorage(std::uint8_t line_count = 6) : line_count_(line_count) {}

  // Queues one edge; returns false when the script is full.
  bool press(std::uint8_t line, bool pressed, ports::TimestampUs t_us) {
    if (count_ == kCapacity) return false;
    edges_[count_++] = {line, pressed, t_us};
    return true;
  }
  void fail(bool failing) {
    failing_ = failing;
    if (!failing) connected_ = true;
  }
  void set_connected(bool connected) { connected_ = connected; }

 private:
  Result<ports::ButtonEdge> do_poll() override {
    if (!connected_) return StatusCode::failed_precondition;
    if (failing_) {
      connected_ = false;
      return StatusCode::io_error;
    }
    if (next_ == count_) return StatusCode::unavailable;
    return edges_[next_++];
  }
  std::uint8_t do_line_count() const override { return line_count_; }
  bool do_connected() const override { return connected_; }

  std::array<ports::ButtonEdge, kCapacity> edges_{};
  std::size_t count_ = 0;
  std::size_t next_ = 0;
  std::uint8_t line_count_;
  bool failing_ = false;
  bool connected_ = true;
};

using FakeButtonSource = FakeButtonSourceWithStorage<>;

}  // namespace twister::test
