#include "twister/hal/hidapi_button_source.hpp"

#include <hidapi/hidapi.h>

namespace twister::hal {

HidapiButtonSource::~HidapiButtonSource() { close(); }

void HidapiButtonSource::close() {
  if (device_ != nullptr) hid_close(device_);
  device_ = nullptr;
  pending_.clear();
}

Status HidapiButtonSource::open(const HidapiButtonConfig& config) {
  close();
  if (&config != &config_) config_ = config;
  configured_ = true;
  TWISTER_TRY(decoder_.configure(config.buttons));
  if (config.buttons.empty()) return StatusCode::invalid_argument;
  if (hid_init() != 0) return StatusCode::io_error;
  if (!config.path.empty()) {
    device_ = hid_open_path(config.path.c_str());
  } else {
    // Enumerate first so "not plugged in" and "cannot open" are told apart.
    hid_device_info* found = hid_enumerate(config.vendor_id, config.product_id);
    if (found == nullptr) return StatusCode::unavailable;
    device_ = hid_open_path(found->path);
    hid_free_enumeration(found);
  }
  if (device_ == nullptr)
    return config.path.empty() ? StatusCode::io_error : StatusCode::unavailable;
  if (hid_set_nonblocking(device_, 1) != 0) {
    close();
    return StatusCode::io_error;
  }
  return ok_status();
}

Status HidapiButtonSource::do_reopen() {
  if (!configured_) return StatusCode::failed_precondition;
  return open(config_);
}

Result<ports::ButtonEdge> HidapiButtonSource::do_poll() {
  if (!pending_.empty()) return take_pending();
  if (device_ == nullptr) return StatusCode::failed_precondition;
  // Drain queued reports until one changes a button (or none is left).
  for (;;) {
    const int n = hid_read(device_, report_.data(), report_.size());
    if (n < 0) {  // unplugged or read error: not connected until reopened
      close();
      return StatusCode::io_error;
    }
    if (n == 0) return StatusCode::unavailable;
    const auto report = std::span(report_.data(), static_cast<std::size_t>(n));
    // pending_ is empty here and holds one edge per button: every edge fits.
    for (const ports::ButtonEdge& e : decoder_.decode(report, clock_.now_us())) {
      pending_.push(e).ignore();
    }
    if (!pending_.empty()) return take_pending();
  }
}

ports::ButtonEdge HidapiButtonSource::take_pending() {
  const ports::ButtonEdge e = pending_.front();
  pending_.pop_front();
  return e;
}

}  // namespace twister::hal
