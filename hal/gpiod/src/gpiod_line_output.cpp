#include "twister/hal/gpiod_line_output.hpp"

#include <gpiod.h>

#include <algorithm>
#include <cerrno>

namespace twister::hal {

GpiodLineOutput::~GpiodLineOutput() { close(); }

void GpiodLineOutput::close() {
  if (count_ > 0) {
    values_.fill(0);
    (void)write_values();  // released inactive: no button left pressed
    for (std::size_t i = 0; i < count_; ++i) gpiod_line_release(lines_[i]);
  }
  lines_.fill(nullptr);
  count_ = 0;
  dirty_ = false;
  if (chip_ != nullptr) gpiod_chip_close(chip_);
  chip_ = nullptr;
}

Status GpiodLineOutput::open(const GpiodOutputConfig& config) {
  close();
  const std::vector<std::uint32_t>& offsets = config.lines;
  if (offsets.empty() || offsets.size() > kMaxLines) return StatusCode::invalid_argument;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    if (std::count(offsets.begin(), offsets.end(), offsets[i]) != 1) {
      return StatusCode::invalid_argument;
    }
  }
  chip_ = gpiod_chip_open_lookup(config.chip.c_str());
  if (chip_ == nullptr) {
    last_errno_ = errno;
    return errno == ENOENT ? StatusCode::unavailable : StatusCode::io_error;
  }
  gpiod_line_bulk bulk;
  gpiod_line_bulk_init(&bulk);
  for (const std::uint32_t offset : offsets) {
    gpiod_line* line = gpiod_chip_get_line(chip_, offset);
    if (line == nullptr) {
      last_errno_ = errno;
      close();
      return StatusCode::invalid_argument;
    }
    gpiod_line_bulk_add(&bulk, line);
  }
  int flags = 0;
  if (config.active_low) flags |= GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW;
  if (config.open_drain) flags |= GPIOD_LINE_REQUEST_FLAG_OPEN_DRAIN;
  values_.fill(0);
  if (gpiod_line_request_bulk_output_flags(&bulk, config.consumer.c_str(), flags, values_.data()) !=
      0) {
    last_errno_ = errno;
    close();
    return StatusCode::io_error;
  }
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    lines_[i] = gpiod_line_bulk_get_line(&bulk, static_cast<unsigned int>(i));
  }
  count_ = offsets.size();
  last_errno_ = 0;
  return ok_status();
}

Status GpiodLineOutput::set(std::size_t index, bool active) {
  if (const Status s = stage(index, active); !s.ok()) return s;
  return flush();
}

Status GpiodLineOutput::stage(std::size_t index, bool active) {
  if (count_ == 0) return StatusCode::failed_precondition;
  if (index >= count_) return StatusCode::invalid_argument;
  dirty_ = dirty_ || values_[index] != (active ? 1 : 0);
  values_[index] = active ? 1 : 0;
  return ok_status();
}

Status GpiodLineOutput::flush() {
  if (!dirty_) return ok_status();
  dirty_ = false;
  return write_values();
}

Status GpiodLineOutput::write_values() {
  gpiod_line_bulk bulk;
  gpiod_line_bulk_init(&bulk);
  for (std::size_t i = 0; i < count_; ++i) gpiod_line_bulk_add(&bulk, lines_[i]);
  if (gpiod_line_set_value_bulk(&bulk, values_.data()) != 0) {
    last_errno_ = errno;
    return StatusCode::io_error;
  }
  return ok_status();
}

}  // namespace twister::hal
