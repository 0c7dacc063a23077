// Test helper: a ByteStream port wired straight to a FastrakDevice in virtual time
// (the PTY path is covered by the termios and acceptance tests).
#pragma once

#include <algorithm>
#include <cstring>
#include <vector>

#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/sim/fastrak_device.hpp"

namespace twister::sim::test {

class DeviceByteStream final : public ports::ByteStream {
 public:
  DeviceByteStream(FastrakDevice& device, ports::Clock& clock) : device_(device), clock_(clock) {}
  std::uint64_t bytes_read = 0;

 private:
  Result<std::size_t> do_read(std::span<std::byte> dest) override {
    const auto now = clock_.now_us();
    if (!open_ || device_.hung_up(now)) {
      open_ = false;
      return StatusCode::io_error;
    }
    device_.advance(now, buf_);
    const std::size_t n = std::min(dest.size(), buf_.size());
    if (n > 0) std::memcpy(dest.data(), buf_.data(), n);
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(n));
    bytes_read += n;
    return n;
  }
  Result<std::size_t> do_write(std::span<const std::byte> src) override {
    const auto now = clock_.now_us();
    if (!open_ || device_.hung_up(now)) return StatusCode::io_error;
    device_.receive(src.data(), src.size(), now);
    return src.size();
  }
  Status do_reopen() override {
    if (device_.hung_up(clock_.now_us())) return StatusCode::unavailable;
    open_ = true;
    buf_.clear();
    return ok_status();
  }
  void do_discard_input() override {
    device_.advance(clock_.now_us(), buf_);
    buf_.clear();
  }

  FastrakDevice& device_;
  ports::Clock& clock_;
  std::vector<std::byte> buf_;
  bool open_ = false;
};

}  // namespace twister::sim::test
