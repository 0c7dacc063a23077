// Storage port: one append-only byte file (the stroke journal). The POSIX backend
// fsyncs in sync(); the test fake can cut power at any byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"

namespace twister::ports {

class Storage {
 public:
  virtual ~Storage() = default;

  // Current length in bytes. io_error: the file cannot be inspected.
  Result<std::uint64_t> size() { return do_size(); }

  // Reads up to dest.size() bytes at offset; returns the count (0 at end).
  Result<std::size_t> read_at(std::uint64_t offset, std::span<std::byte> dest) {
    return do_read_at(offset, dest);
  }

  // Appends all of src or fails. io_error: write failed (partial data may be on disk;
  // readers must detect torn records).
  Status append(std::span<const std::byte> src) { return do_append(src); }

  // Makes appended bytes durable (fsync). io_error on failure.
  Status sync() { return do_sync(); }

  // Cuts the file to length bytes (drops a torn tail). io_error on failure.
  Status truncate(std::uint64_t length) { return do_truncate(length); }

 private:
  virtual Result<std::uint64_t> do_size() = 0;
  virtual Result<std::size_t> do_read_at(std::uint64_t offset, std::span<std::byte> dest) = 0;
  virtual Status do_append(std::span<const std::byte> src) = 0;
  virtual Status do_sync() = 0;
  virtual Status do_truncate(std::uint64_t length) = 0;
};

}  // namespace twister::ports
