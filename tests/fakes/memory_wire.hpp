// In-memory LinkPort pair for link tests: what one end sends the other receives.
// `up` false = cable pulled: both ends get unavailable and bytes in flight are
// lost. `capacity` bounds bytes in flight per direction (a slow peer). The rings
// are allocated once at construction, so send/receive never allocate (the
// no-heap checks measure the code under test, not this double).
#pragma once

#include <cstddef>
#include <vector>

#include "twister/ports/link_port.hpp"

namespace twister::test {

class ByteRing {
 public:
  explicit ByteRing(std::size_t size) : data_(size) {}
  bool push(std::byte b) {
    if (count_ == data_.size()) return false;
    data_[(head_ + count_) % data_.size()] = b;
    ++count_;
    return true;
  }
  std::byte pop() {
    const std::byte b = data_[head_];
    head_ = (head_ + 1) % data_.size();
    --count_;
    return b;
  }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  void clear() { head_ = count_ = 0; }
  // Line noise: flips bits of the byte `offset` bytes after the oldest one.
  void flip(std::size_t offset, std::byte mask) {
    if (offset < count_) data_[(head_ + offset) % data_.size()] ^= mask;
  }

 private:
  std::vector<std::byte> data_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

struct MemoryWire {
  ByteRing a_to_b{std::size_t{1} << 23};
  ByteRing b_to_a{std::size_t{1} << 20};
  bool up = true;
  std::size_t capacity = std::size_t{1} << 23;
  void cut() {
    up = false;
    a_to_b.clear();
    b_to_a.clear();
  }
};

class MemoryLinkEnd final : public ports::LinkPort {
 public:
  MemoryLinkEnd(MemoryWire& wire, bool is_a) : wire_(wire), is_a_(is_a) {}

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override {
    if (!wire_.up) return StatusCode::unavailable;
    ByteRing& q = is_a_ ? wire_.a_to_b : wire_.b_to_a;
    std::size_t n = 0;
    while (n < src.size() && q.size() < wire_.capacity && q.push(src[n])) ++n;
    return n;
  }
  Result<std::size_t> do_receive(std::span<std::byte> dest) override {
    if (!wire_.up) return StatusCode::unavailable;
    ByteRing& q = is_a_ ? wire_.b_to_a : wire_.a_to_b;
    std::size_t n = 0;
    while (n < dest.size() && !q.empty()) dest[n++] = q.pop();
    return n;
  }
  MemoryWire& wire_;
  bool is_a_;
};

}  // namespace twister::test
