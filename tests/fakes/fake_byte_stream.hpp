// FakeByteStream: a scripted serial port. The test pushes bytes for the core to
// read, reads back what the core wrote, and can unplug / re-plug the device.
// Fixed capacity, no allocation (usable inside no-allocation scopes).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <span>
#include <string_view>

#include "twister/ports/byte_stream.hpp"

namespace twister::test {

template <std::size_t kCapacity = 1 << 16>
class FakeByteStreamWithStorage final : public ports::ByteStream {
 public:
  // Test side -------------------------------------------------------------
  // Queues bytes for the core to read; returns how many fitted.
  std::size_t push_rx(std::span<const std::byte> bytes) {
    const std::size_t n = std::min(bytes.size(), kCapacity - rx_len_);
    std::memcpy(rx_.data() + rx_len_, bytes.data(), n);
    rx_len_ += n;
    return n;
  }
  std::size_t push_rx(std::string_view text) {
    return push_rx(std::as_bytes(std::span<const char>(text.data(), text.size())));
  }
  // Everything the core wrote since the last clear_tx().
  std::string_view tx() const { return {reinterpret_cast<const char*>(tx_.data()), tx_len_}; }
  void clear_tx() { tx_len_ = 0; }

  void unplug() {
    connected_ = false;
    rx_len_ = 0;
    rx_pos_ = 0;
  }
  void set_present(bool present) { plugged_ = present; }
  // A hot-plug arrival: device_arrived() says true until the next reopen().
  void announce_arrival() { arrived_ = true; }
  bool connected() const { return connected_; }
  int reopen_count() const { return reopen_count_; }

 private:
  Result<std::size_t> do_read(std::span<std::byte> dest) override {
    if (!connected_) return StatusCode::io_error;
    const std::size_t n = std::min(dest.size(), rx_len_ - rx_pos_);
    std::memcpy(dest.data(), rx_.data() + rx_pos_, n);
    rx_pos_ += n;
    if (rx_pos_ == rx_len_) rx_pos_ = rx_len_ = 0;
    return n;
  }
  Result<std::size_t> do_write(std::span<const std::byte> src) override {
    if (!connected_) return StatusCode::io_error;
    const std::size_t n = std::min(src.size(), kCapacity - tx_len_);
    std::memcpy(tx_.data() + tx_len_, src.data(), n);
    tx_len_ += n;
    return n;
  }
  bool do_device_arrived() override { return arrived_; }
  Status do_reopen() override {
    ++reopen_count_;
    arrived_ = false;
    if (!plugged_) return StatusCode::unavailable;
    connected_ = true;
    rx_len_ = rx_pos_ = 0;
    return ok_status();
  }
  void do_discard_input() override { rx_len_ = rx_pos_ = 0; }

  std::array<std::byte, kCapacity> rx_{};
  std::array<std::byte, kCapacity> tx_{};
  std::size_t rx_len_ = 0;
  std::size_t rx_pos_ = 0;
  std::size_t tx_len_ = 0;
  bool connected_ = true;
  bool plugged_ = true;
  bool arrived_ = false;
  int reopen_count_ = 0;
};

using FakeByteStream = FakeByteStreamWithStorage<>;

}  // namespace twister::test
