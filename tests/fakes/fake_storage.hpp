// FakeStorage: an in-memory append-only file for core tests. It can cut power at
// any byte of an append (the bytes before the cut stay, the call fails and every
// later call fails until power_on()), fail syncs, fill the disk at a size (an append
// past it writes what fits and fails, like write(2) with ENOSPC; later calls work),
// fail truncates, and flip bytes to simulate corruption. Fixed capacity, no
// allocation (usable in no-allocation scopes).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>

#include "twister/ports/storage.hpp"

namespace twister::test {

template <std::size_t kCapacity = 1 << 16>
class FakeStorageWithStorage final : public ports::Storage {
 public:
  // Test side -------------------------------------------------------------
  // The next appends write `bytes` more bytes in total, then power goes off.
  void cut_power_after(std::size_t bytes) { budget_ = bytes; }
  void power_on() {
    powered_ = true;
    budget_ = kNoCut;
  }
  bool powered() const { return powered_; }
  void fail_next_sync() { fail_sync_ = true; }
  // The disk is full once the file holds `bytes` (at most the capacity).
  void fill_disk_at(std::size_t bytes) { limit_ = std::min(bytes, kCapacity); }
  void free_disk() { limit_ = kCapacity; }
  void fail_truncates(bool fail) { fail_truncate_ = fail; }
  void corrupt(std::size_t offset, std::byte xor_mask) { data_[offset] ^= xor_mask; }
  void load(std::span<const std::byte> bytes) {
    size_ = std::min(bytes.size(), kCapacity);
    std::memcpy(data_.data(), bytes.data(), size_);
  }
  std::span<const std::byte> bytes() const { return {data_.data(), size_}; }
  std::size_t sync_count() const { return sync_count_; }
  std::size_t synced_size() const { return synced_size_; }

 private:
  static constexpr std::size_t kNoCut = std::numeric_limits<std::size_t>::max();

  Result<std::uint64_t> do_size() override {
    if (!powered_) return StatusCode::io_error;
    return static_cast<std::uint64_t>(size_);
  }
  Result<std::size_t> do_read_at(std::uint64_t offset, std::span<std::byte> dest) override {
    if (!powered_) return StatusCode::io_error;
    if (offset >= size_) return std::size_t{0};
    const std::size_t n =
        std::min<std::size_t>(dest.size(), size_ - static_cast<std::size_t>(offset));
    std::memcpy(dest.data(), data_.data() + offset, n);
    return n;
  }
  Status do_append(std::span<const std::byte> src) override {
    if (!powered_) return StatusCode::io_error;
    std::size_t n = std::min(src.size(), limit_ > size_ ? limit_ - size_ : std::size_t{0});
    const bool cut = budget_ != kNoCut && budget_ < n;
    if (budget_ != kNoCut) n = std::min(n, budget_);
    std::memcpy(data_.data() + size_, src.data(), n);
    size_ += n;
    if (budget_ != kNoCut) budget_ -= n;
    if (cut) {
      powered_ = false;
      return StatusCode::io_error;
    }
    if (n < src.size()) return StatusCode::io_error;  // disk full
    return ok_status();
  }
  Status do_sync() override {
    if (!powered_) return StatusCode::io_error;
    if (fail_sync_) {
      fail_sync_ = false;
      return StatusCode::io_error;
    }
    ++sync_count_;
    synced_size_ = size_;
    return ok_status();
  }
  Status do_truncate(std::uint64_t length) override {
    if (!powered_ || fail_truncate_) return StatusCode::io_error;
    size_ = std::min<std::size_t>(size_, static_cast<std::size_t>(length));
    return ok_status();
  }

  std::array<std::byte, kCapacity> data_{};
  std::size_t size_ = 0;
  std::size_t budget_ = kNoCut;
  bool powered_ = true;
  bool fail_sync_ = false;
  bool fail_truncate_ = false;
  std::size_t limit_ = kCapacity;
  std::size_t sync_count_ = 0;
  std::size_t synced_size_ = 0;
};

using FakeStorage = FakeStorageWithStorage<>;

}  // namespace twister::test
