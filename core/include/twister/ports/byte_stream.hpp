// ByteStream port: a non-blocking, reopenable byte link (tracker serial/USB, PTY,
// in-process simulator). Backends only move bytes; parsing is core's job.
#pragma once

#include <cstddef>
#include <span>

#include "twister/base/result.hpp"

namespace twister::ports {

class ByteStream {
 public:
  virtual ~ByteStream() = default;

  // Copies the bytes available now into dest (never blocks).
  // Returns the count, 0 when nothing is pending.
  // io_error: the device hung up or was unplugged; call reopen() later.
  Result<std::size_t> read(std::span<std::byte> dest) { return do_read(dest); }

  // Queues bytes for transmission; may accept fewer than src.size() (returns count).
  // io_error: disconnected.
  Result<std::size_t> write(std::span<const std::byte> src) { return do_write(src); }

  // (Re)opens the device with its configured settings and drops stale input.
  // unavailable: not present yet (unplugged); io_error: present but failed to open.
  Status reopen() { return do_reopen(); }

  // Discards bytes received but not yet read (after a reset command, say).
  void discard_input() { do_discard_input(); }

  // true when the device has just appeared (a hot-plug arrival since the last
  // reopen()): a hint to reopen now instead of at the end of a back-off. Never
  // blocks. A backend without hot-plug says false (the default).
  bool device_arrived() { return do_device_arrived(); }

 private:
  virtual bool do_device_arrived() { return false; }
  virtual Result<std::size_t> do_read(std::span<std::byte> dest) = 0;
  virtual Result<std::size_t> do_write(std::span<const std::byte> src) = 0;
  virtual Status do_reopen() = 0;
  virtual void do_discard_input() = 0;
};

}  // namespace twister::ports
