// Journal storage for benchmarks that keeps only the length: they measure the
// session, not the disk (a real fsync is the POSIX backend's cost).
#pragma once

#include <cstdint>
#include <span>

#include "twister/ports/storage.hpp"

namespace twister::bench {

class CountingStorage final : public ports::Storage {
  Result<std::uint64_t> do_size() override { return size_; }
  Result<std::size_t> do_read_at(std::uint64_t, std::span<std::byte>) override {
    return std::size_t{0};
  }
  Status do_append(std::span<const std::byte> src) override {
    size_ += src.size();
    return ok_status();
  }
  Status do_sync() override { return ok_status(); }
  Status do_truncate(std::uint64_t length) override {
    size_ = length;
    return ok_status();
  }
  std::uint64_t size_ = 0;
};

}  // namespace twister::bench
