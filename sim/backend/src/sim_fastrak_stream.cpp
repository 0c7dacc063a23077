#include "twister/sim/sim_fastrak_stream.hpp"

#include <array>
#include <utility>

namespace twister::sim {

SimFastrakStream::SimFastrakStream(ports::Clock& clock, const FastrakDeviceConfig& config,
                                   Scenario scenario)
    : clock_(clock), device_(config, std::move(scenario), clock.now_us()) {}

Result<std::size_t> SimFastrakStream::do_read(std::span<std::byte> dest) {
  if (!connected_) return StatusCode::io_error;
  const ports::TimestampUs now = clock_.now_us();
  if (device_.hung_up(now)) {
    // Like a USB-serial adapter pulled out: what was not read is gone.
    connected_ = false;
    return StatusCode::io_error;
  }
  return device_.advance(now, dest);
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
  return ok_status();
}

void SimFastrakStream::do_discard_input() {
  // Drops what has arrived by now.
  std::array<std::byte, 256> sink{};
  while (device_.advance(clock_.now_us(), sink) > 0) {
  }
}

}  // namespace twister::sim
