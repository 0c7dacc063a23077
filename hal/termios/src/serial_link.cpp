#include "twister/hal/serial_link.hpp"

#include <time.h>

#include <cstring>

namespace twister::hal {
namespace {

std::int64_t now_ms() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000 + ts.tv_nsec / 1'000'000;
}

}  // namespace

SerialLink::SerialLink(const SerialLinkConfig& config)
    : config_(config), tty_(TermiosConfig{config.path, config.baud, config.flow}) {}

Expected<void> SerialLink::open() {
  unsigned speed = 0;
  if (!baud_to_speed(config_.baud, speed)) {
    return make_error(
        StatusCode::invalid_argument,
        "serial link " + config_.path + ": unsupported baud rate " + std::to_string(config_.baud));
  }
  const Status s = static_cast<PollSource&>(tty_).reopen();
  next_attempt_ms_ = now_ms() + config_.reopen_interval_ms;
  if (s.ok()) return {};
  return make_error(s.code(), "serial link " + config_.path + ": " + s.name() + " (" +
                                  std::strerror(tty_.last_errno()) + ")");
}

Status SerialLink::do_reopen() {
  next_attempt_ms_ = now_ms() + config_.reopen_interval_ms;
  return static_cast<PollSource&>(tty_).reopen();
}

bool SerialLink::ensure_open() {
  if (tty_.is_open()) return true;
  const std::int64_t now = now_ms();
  if (now < next_attempt_ms_) return false;
  return do_reopen().ok();
}

Result<std::size_t> SerialLink::do_send(std::span<const std::byte> src) {
  if (!ensure_open()) return StatusCode::unavailable;
  Result<std::size_t> n = tty_.write(src);
  if (!n.ok()) return StatusCode::unavailable;  // unplugged: reopened later
  return n;
}

Result<std::size_t> SerialLink::do_receive(std::span<std::byte> dest) {
  if (!ensure_open()) return StatusCode::unavailable;
  Result<std::size_t> n = tty_.read(dest);
  if (!n.ok()) return StatusCode::unavailable;
  return n;
}

}  // namespace twister::hal
