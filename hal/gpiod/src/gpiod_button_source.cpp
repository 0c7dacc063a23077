#include "twister/hal/gpiod_button_source.hpp"

#include <gpiod.h>
#include <poll.h>

#include <cerrno>

namespace twister::hal {
namespace {
constexpr const char* kConsumer = "twister-station";
}  // namespace

GpiodButtonSource::~GpiodButtonSource() { close(); }

void GpiodButtonSource::close() {
  for (const RequestedLine& l : lines_) {
    if (l.line != nullptr) gpiod_line_release(l.line);
  }
  lines_.clear();
  if (chip_ != nullptr) gpiod_chip_close(chip_);
  chip_ = nullptr;
}

Status GpiodButtonSource::open(const GpiodButtonConfig& config) {
  close();
  if (&config != &config_) config_ = config;
  configured_ = true;
  if (config.lines.empty() || config.lines.size() > kMaxLines) return StatusCode::invalid_argument;
  chip_ = gpiod_chip_open_lookup(config.chip.c_str());
  if (chip_ == nullptr) {
    last_errno_ = errno;
    return errno == ENOENT ? StatusCode::unavailable : StatusCode::io_error;
  }
  int flags = config.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  switch (config.bias) {
    case GpiodButtonConfig::Bias::as_is:
      break;
    case GpiodButtonConfig::Bias::disable:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
      break;
    case GpiodButtonConfig::Bias::pull_up:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
      break;
    case GpiodButtonConfig::Bias::pull_down:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
      break;
  }
  // One request per line (v1 event requests are per line anyway); each line's fd
  // joins the event loop's poll set.
  for (const std::uint32_t offset : config.lines) {
    gpiod_line* line = gpiod_chip_get_line(chip_, offset);
    if (line == nullptr) {
      last_errno_ = errno;
      close();
      return StatusCode::invalid_argument;
    }
    if (gpiod_line_request_both_edges_events_flags(line, kConsumer, flags) != 0) {
      last_errno_ = errno;
      close();
      return StatusCode::io_error;
    }
    // Fits: config.lines.size() <= kMaxLines was checked above.
    lines_.push_back({line, gpiod_line_event_get_fd(line)}).ignore();
  }
  next_line_ = 0;
  last_errno_ = 0;
  return ok_status();
}

std::size_t GpiodButtonSource::do_poll_fds(std::span<pollfd> out) const {
  std::size_t n = 0;
  for (; n < lines_.size() && n < out.size(); ++n) out[n] = {lines_[n].fd, POLLIN, 0};
  return n;
}

Status GpiodButtonSource::do_reopen() {
  if (!configured_) return StatusCode::failed_precondition;
  return open(config_);
}

Result<ports::ButtonEdge> GpiodButtonSource::do_poll() {
  const std::size_t count = lines_.size();
  if (count == 0) return StatusCode::failed_precondition;
  std::array<pollfd, kMaxLines> pfds{};
  for (std::size_t i = 0; i < count; ++i) pfds[i] = {lines_[i].fd, POLLIN, 0};
  const int n = ::poll(pfds.data(), count, 0);
  if (n < 0) {
    last_errno_ = errno;
    return errno == EINTR ? StatusCode::unavailable : StatusCode::io_error;
  }
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = (next_line_ + k) % count;
    if ((pfds[i].revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 &&
        (pfds[i].revents & POLLIN) == 0) {
      close();  // the chip is gone: not connected until reopened
      last_errno_ = ENODEV;
      return StatusCode::io_error;
    }
    if ((pfds[i].revents & POLLIN) == 0) continue;
    gpiod_line_event event{};
    if (gpiod_line_event_read_fd(lines_[i].fd, &event) != 0) {
      last_errno_ = errno;
      close();
      return StatusCode::io_error;
    }
    next_line_ = (i + 1) % count;
    ports::ButtonEdge edge;
    edge.line = static_cast<std::uint8_t>(i);
    edge.pressed = event.event_type == GPIOD_LINE_EVENT_RISING_EDGE;
    edge.time_us =
        static_cast<ports::TimestampUs>(event.ts.tv_sec) * 1'000'000 + event.ts.tv_nsec / 1'000;
    return edge;
  }
  return StatusCode::unavailable;
}

}  // namespace twister::hal
