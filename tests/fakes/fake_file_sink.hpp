// FakeFileSink: an in-memory FileSink for core tests and fuzz harnesses. What commit()
// publishes is bytes(); a failure can be injected at a byte count (a full disk) and
// commit() can be made to fail. Fixed capacity, no allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <span>

#include "twister/ports/file_sink.hpp"

namespace twister::test {

template <std::size_t kCapacity = 1 << 16>
class FakeFileSinkWithStorage final : public ports::FileSink {
 public:
  // The committed file (empty until the first commit()).
  std::span<const std::byte> bytes() const { return {committed_.data(), committed_size_}; }
  std::size_t commits() const { return commits_; }
  bool open() const { return open_; }
  void fail_writes_after(std::size_t bytes) { limit_ = bytes; }
  void fail_next_commit() { fail_commit_ = true; }

 private:
  Status do_begin() override {
    open_ = true;
    size_ = 0;
    return ok_status();
  }
  Status do_write(std::span<const std::byte> src) override {
    if (!open_) return StatusCode::failed_precondition;
    const std::size_t room =
        std::min(kCapacity, limit_) - std::min(size_, std::min(kCapacity, limit_));
    if (src.size() > room) return StatusCode::io_error;
    std::memcpy(temp_.data() + size_, src.data(), src.size());
    size_ += src.size();
    return ok_status();
  }
  Status do_commit() override {
    if (!open_) return StatusCode::failed_precondition;
    open_ = false;
    if (fail_commit_) {
      fail_commit_ = false;
      return StatusCode::io_error;
    }
    std::memcpy(committed_.data(), temp_.data(), size_);
    committed_size_ = size_;
    ++commits_;
    return ok_status();
  }
  void do_abort() override { open_ = false; }

  std::array<std::byte, kCapacity> temp_{};
  std::array<std::byte, kCapacity> committed_{};
  std::size_t size_ = 0;
  std::size_t committed_size_ = 0;
  std::size_t commits_ = 0;
  std::size_t limit_ = kCapacity;
  bool open_ = false;
  bool fail_commit_ = false;
};

using FakeFileSink = FakeFileSinkWithStorage<>;

}  // namespace twister::test
