// LibusbByteStream: LIBUSB_ERROR_* is translated to StatusCode here, at the boundary.
#include "twister/hal/libusb_byte_stream.hpp"

#include <libusb.h>
#include <poll.h>

#include <algorithm>

namespace twister::hal {

struct LibusbCallbacks {
  static void on_in_transfer(libusb_transfer* transfer);
  static int on_hotplug(libusb_context* ctx, libusb_device* device, libusb_hotplug_event event,
                        void* self);
  static void on_fd_added(int fd, short events, void* self) {
    static_cast<LibusbByteStream*>(self)->add_fd(fd, events);
  }
  static void on_fd_removed(int fd, void* self) {
    static_cast<LibusbByteStream*>(self)->remove_fd(fd);
  }
};

LibusbByteStream::~LibusbByteStream() {
  close();
  if (in_transfer_ != nullptr) libusb_free_transfer(in_transfer_);
  if (ctx_ != nullptr) libusb_exit(ctx_);
}

Status LibusbByteStream::init() {
  if ((config_.endpoint_in & LIBUSB_ENDPOINT_IN) == 0 ||
      (config_.endpoint_out & LIBUSB_ENDPOINT_IN) != 0) {
    return StatusCode::invalid_argument;
  }
  if (ctx_ != nullptr) return ok_status();
  if (const int rc = libusb_init(&ctx_); rc != 0) {
    ctx_ = nullptr;
    last_error_ = rc;
    return StatusCode::io_error;
  }
  // The descriptors to wait on: libusb's list once, then its notifications.
  libusb_set_pollfd_notifiers(ctx_, &LibusbCallbacks::on_fd_added, &LibusbCallbacks::on_fd_removed,
                              this);
  if (const libusb_pollfd** list = libusb_get_pollfds(ctx_); list != nullptr) {
    for (std::size_t i = 0; list[i] != nullptr; ++i) add_fd(list[i]->fd, list[i]->events);
    libusb_free_pollfds(list);
  }
  in_transfer_ = libusb_alloc_transfer(0);
  if (in_transfer_ == nullptr) return StatusCode::resource_exhausted;
  if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) != 0) {
    const int rc = libusb_hotplug_register_callback(
        ctx_,
        static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                          LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
        LIBUSB_HOTPLUG_NO_FLAGS, config_.vendor_id, config_.product_id, LIBUSB_HOTPLUG_MATCH_ANY,
        &LibusbCallbacks::on_hotplug, this, nullptr);
    hotplug_ = rc == LIBUSB_SUCCESS;
    if (!hotplug_) last_error_ = rc;
  }
  return ok_status();
}

int LibusbCallbacks::on_hotplug(libusb_context*, libusb_device*, libusb_hotplug_event event,
                                void* self) {
  auto* s = static_cast<LibusbByteStream*>(self);
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED) s->arrived_ = true;
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT && s->handle_ != nullptr) s->removed_ = true;
  return 0;  // stay registered
}

void LibusbCallbacks::on_in_transfer(libusb_transfer* transfer) {
  auto* s = static_cast<LibusbByteStream*>(transfer->user_data);
  s->in_flight_ = false;
  if (transfer->status == LIBUSB_TRANSFER_COMPLETED ||
      transfer->status == LIBUSB_TRANSFER_TIMED_OUT) {
    const auto n = static_cast<std::size_t>(std::max(transfer->actual_length, 0));
    for (std::size_t i = 0; i < n; ++i) {
      if (!s->rx_.push(static_cast<std::byte>(s->in_buffer_[i])).ok()) {
        s->rx_dropped_ += n - i;
        break;
      }
    }
    if (s->handle_ != nullptr && libusb_submit_transfer(transfer) == 0) s->in_flight_ = true;
    return;
  }
  if (transfer->status == LIBUSB_TRANSFER_NO_DEVICE || transfer->status == LIBUSB_TRANSFER_ERROR) {
    s->removed_ = true;
    s->last_error_ = LIBUSB_ERROR_NO_DEVICE;
  }
  // LIBUSB_TRANSFER_CANCELLED: close() asked for it.
}

void LibusbByteStream::pump_events() {
  if (ctx_ == nullptr) return;
  timeval zero{0, 0};
  libusb_handle_events_timeout_completed(ctx_, &zero, nullptr);
}

void LibusbByteStream::add_fd(int fd, short events) {
  for (pollfd& p : usb_fds_) {
    if (p.fd == fd) {
      p.events = events;
      return;
    }
  }
  usb_fds_.push_back({fd, events, 0}).ignore();  // more than kMaxFds: not polled
}

void LibusbByteStream::remove_fd(int fd) {
  for (pollfd& p : usb_fds_) {
    if (p.fd == fd) {
      p = usb_fds_.back();  // order does not matter: the last one takes its place
      usb_fds_.pop_back();
      return;
    }
  }
}

std::size_t LibusbByteStream::do_poll_fds(std::span<pollfd> out) const {
  if (handle_ == nullptr) return 0;
  const std::size_t n = std::min(usb_fds_.size(), out.size());
  std::copy_n(usb_fds_.begin(), n, out.begin());
  return n;
}

Status LibusbByteStream::gone(int error) {
  last_error_ = error;
  close();
  return StatusCode::io_error;
}

void LibusbByteStream::close() {
  if (handle_ == nullptr) return;
  if (in_flight_) {
    libusb_cancel_transfer(in_transfer_);
    // The cancellation completes through the event loop; wait for it so the buffer
    // is no longer in use when the handle goes.
    for (int i = 0; i < 100 && in_flight_; ++i) {
      timeval tv{0, 10'000};
      libusb_handle_events_timeout_completed(ctx_, &tv, nullptr);
    }
    in_flight_ = false;
  }
  libusb_release_interface(handle_, config_.interface_number);
  libusb_close(handle_);
  handle_ = nullptr;
  removed_ = false;
}

Status LibusbByteStream::do_reopen() {
  if (ctx_ == nullptr) return StatusCode::failed_precondition;
  close();
  arrived_ = false;
  rx_.clear();
  handle_ = libusb_open_device_with_vid_pid(ctx_, config_.vendor_id, config_.product_id);
  if (handle_ == nullptr) return StatusCode::unavailable;
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  if (const int rc = libusb_claim_interface(handle_, config_.interface_number); rc != 0) {
    last_error_ = rc;
    libusb_close(handle_);
    handle_ = nullptr;
    return StatusCode::io_error;
  }
  libusb_fill_bulk_transfer(in_transfer_, handle_, config_.endpoint_in, in_buffer_.data(),
                            static_cast<int>(in_buffer_.size()), &LibusbCallbacks::on_in_transfer,
                            this, 0);
  if (const int rc = libusb_submit_transfer(in_transfer_); rc != 0) return gone(rc);
  in_flight_ = true;
  return ok_status();
}

Result<std::size_t> LibusbByteStream::do_read(std::span<std::byte> dest) {
  if (handle_ == nullptr) return StatusCode::io_error;
  pump_events();
  if (removed_) return gone(LIBUSB_ERROR_NO_DEVICE);
  if (!in_flight_) {
    if (const int rc = libusb_submit_transfer(in_transfer_); rc != 0) return gone(rc);
    in_flight_ = true;
  }
  return rx_.pop_front_into(dest);
}

Result<std::size_t> LibusbByteStream::do_write(std::span<const std::byte> src) {
  if (handle_ == nullptr) return StatusCode::io_error;
  if (removed_) return gone(LIBUSB_ERROR_NO_DEVICE);
  int sent = 0;
  // libusb's API takes a non-const buffer for both directions; OUT does not write it.
  auto* data = const_cast<unsigned char*>(reinterpret_cast<const unsigned char*>(src.data()));
  const int rc = libusb_bulk_transfer(handle_, config_.endpoint_out, data,
                                      static_cast<int>(src.size()), &sent, config_.timeout_ms);
  if (rc == LIBUSB_ERROR_NO_DEVICE || rc == LIBUSB_ERROR_IO || rc == LIBUSB_ERROR_PIPE)
    return gone(rc);
  if (rc != 0 && rc != LIBUSB_ERROR_TIMEOUT) {
    last_error_ = rc;
    return StatusCode::io_error;
  }
  return static_cast<std::size_t>(std::max(sent, 0));  // a timeout may have sent part
}

void LibusbByteStream::do_discard_input() {
  pump_events();
  rx_.clear();
}

}  // namespace twister::hal
