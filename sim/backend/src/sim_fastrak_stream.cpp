#include "twister/sim/sim_fastrak_stream.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace twister::sim {

SimFastrakStream::SimFastrakStream(ports::Clock& clock, const FastrakDeviceConfig& config,
                                   Scenario scenario)
    : clock_(clock), device_(config, std::move(scenario), clock.now_us()) {
  pending_.reserve(4096);
}

Result<std::size_t> SimFastrakStream::do_read(std::span<std::byte> dest) {
  if (!connected_) return StatusCode::io_error;
  const ports::TimestampUs now = clock_.now_us();
  if (device_.hung_up(now)) {
    // Like a USB-serial adapter pulled out: what was not read is gone.
    connected_ = false;
    pending_.clear();
    pending_pos_ = 0;
    return StatusCode::io_error;
  }
  if (pending_pos_ == pending_.size()) {
    pending_.clear();
    pending_pos_ = 0;
  }
  device_.advance(now, pending_);
  const std::size_t n = std::min(dest.size(), pending_.size() - pending_pos_);
  std::memcpy(dest.data(), pending_.data() + pending_pos_, n);
  pending_pos_ += n;
  return n;
}

Result<std::size_t> SimFastrakStream::do_write(std::span<const std::byte> src) {
  if (!connected_) return StatusCode::io_error;
  const ports::TimestampUs now = clock_.now_us();
  if (device_.hung_up(now)) {
    connected_ = false;
    return StatusCode::io_error;
  }
  device_.receive(src.data(), src.size(), now);
  return src.size();
}

Status SimFastrakStream::do_reopen() {
  if (device_.hung_up(clock_.now_us())) return StatusCode::unavailable;
  connected_ = true;
  pending_.clear();
  pending_pos_ = 0;
  return ok_status();
}

void SimFastrakStream::do_discard_input() {
  device_.advance(clock_.now_us(), pending_);  // drop what has arrived by now, too
  pending_.clear();
  pending_pos_ = 0;
}

}  // namespace twister::sim
