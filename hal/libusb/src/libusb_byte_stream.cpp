// LibusbByteStream: LIBUSB_ERROR_* is translated to StatusCode here, at the boundary.
#include "twister/hal/libusb_byte_stream.hpp"

#include <libusb.h>
#include <poll.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>

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
  if ((config_.endpoint_in != 0 && (config_.endpoint_in & LIBUSB_ENDPOINT_IN) == 0) ||
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
        LIBUSB_HOTPLUG_NO_FLAGS, config_.vendor_id,
        config_.product_id != 0 ? config_.product_id : LIBUSB_HOTPLUG_MATCH_ANY,
        LIBUSB_HOTPLUG_MATCH_ANY, &LibusbCallbacks::on_hotplug, this, nullptr);
    hotplug_ = rc == LIBUSB_SUCCESS;
    if (!hotplug_) last_error_ = rc;
  }
  return ok_status();
}

int LibusbCallbacks::on_hotplug(libusb_context*, libusb_device* device, libusb_hotplug_event event,
                                void* self) {
  auto* s = static_cast<LibusbByteStream*>(self);
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED) s->arrived_ = true;
  // Only the device in use: another unit of the vendor leaving changes nothing here.
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT && s->handle_ != nullptr &&
      libusb_get_device(s->handle_) == device) {
    s->removed_ = true;
  }
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
    // Back-pressure: the next transfer only while the ring has room for all it may
    // bring; until read() makes room the unit keeps its data (USB flow control).
    // Never while close() waits for the cancelled transfer: a transfer that completed
    // before the cancellation took effect would otherwise go out again and stay in
    // flight as the handle is closed.
    if (s->handle_ != nullptr && !s->closing_ && s->room_for_transfer() &&
        libusb_submit_transfer(transfer) == 0)
      s->in_flight_ = true;
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
  if (handle_ != nullptr && found_.product_id != 0) {
    report(Level::warning,
           "USB: %s (%04x:%04x) on bus %03u device %03u is gone (%s); looking for it again",
           found_.id != nullptr ? found_.id->name : "the tracker",
           static_cast<unsigned>(config_.vendor_id), static_cast<unsigned>(found_.product_id),
           static_cast<unsigned>(found_.bus), static_cast<unsigned>(found_.address),
           libusb_error_name(error));
  }
  close();
  return StatusCode::io_error;
}

void LibusbByteStream::close() {
  if (handle_ == nullptr) return;
  closing_ = true;
  bool stuck = false;
  if (in_flight_) {
    libusb_cancel_transfer(in_transfer_);
    // The cancellation completes through the event loop; wait for it so the buffer
    // is no longer in use when the handle goes.
    for (int i = 0; i < 100 && in_flight_; ++i) {
      timeval tv{0, 10'000};
      libusb_handle_events_timeout_completed(ctx_, &tv, nullptr);
    }
    stuck = in_flight_;
    in_flight_ = false;
  }
  libusb_release_interface(handle_, config_.interface_number);
  libusb_close(handle_);
  handle_ = nullptr;
  if (stuck) {
    // The cancelled transfer never came back: libusb_close took it off libusb's list
    // (closing the descriptor ends the URB) but leaves it flagged in flight, so it could
    // never be submitted again (LIBUSB_ERROR_BUSY at every reopen). A fresh one instead.
    libusb_free_transfer(in_transfer_);
    in_transfer_ = libusb_alloc_transfer(0);
  }
  removed_ = false;
  closing_ = false;
}

bool LibusbByteStream::do_device_arrived() {
  if (handle_ != nullptr || !hotplug_) return false;
  pump_events();  // delivers the hot-plug callbacks
  return arrived_;
}

void LibusbByteStream::report(Level level, const char* format, ...) {
  std::array<char, 512> line{};
  va_list args;
  va_start(args, format);
  std::vsnprintf(line.data(), line.size(), format, args);
  va_end(args);
  if (level == report_.level && std::strcmp(line.data(), report_.text.data()) == 0) return;
  report_.text = line;
  report_.level = level;
  ++report_.changes;
}

void LibusbByteStream::describe_wanted(char* out, std::size_t size) const {
  std::size_t n = 0;
  out[0] = '\0';
  auto add = [&](const char* name, std::uint16_t product) {
    if (n >= size) return;
    const int w = std::snprintf(out + n, size - n, "%s%s (%04x:%04x)", n > 0 ? ", " : "", name,
                                config_.vendor_id, product);
    if (w > 0) n += static_cast<std::size_t>(w);
  };
  if (config_.product_id != 0) {
    const PolhemusUsbId* id = find_polhemus_usb_id(config_.vendor_id, config_.product_id);
    add(id != nullptr ? id->name : "a tracker", config_.product_id);
    return;
  }
  for (auto m : {PolhemusUsbModel::fastrak, PolhemusUsbModel::fastrak3, PolhemusUsbModel::liberty,
                 PolhemusUsbModel::patriot, PolhemusUsbModel::latus}) {
    if ((config_.models & polhemus_model_bit(m)) != 0)
      add(polhemus_model_name(m), polhemus_running_id(m));
  }
}

namespace {

// How a device on the bus relates to what the search wants; the best kind wins.
enum class Match : std::uint8_t { none, other, needs_firmware, usable };

// The best device of the list for `config`: one it can use, else one that needs its
// firmware, else another Polhemus unit (reported), else none.
struct Candidate {
  Match match = Match::none;
  libusb_device* device = nullptr;
  const PolhemusUsbId* id = nullptr;
  std::uint16_t product = 0;
};

Candidate best_candidate(const LibusbConfig& config, libusb_device** list, ssize_t count) {
  Candidate best;
  for (ssize_t i = 0; i < count; ++i) {
    libusb_device_descriptor d{};
    if (libusb_get_device_descriptor(list[i], &d) != 0 || d.idVendor != config.vendor_id) continue;
    const PolhemusUsbId* id = find_polhemus_usb_id(d.idVendor, d.idProduct);
    const bool wanted_model =
        id != nullptr && id->model != PolhemusUsbModel::unsupported &&
        (config.product_id != 0 ? polhemus_running_id(id->model) == config.product_id
                                : (config.models & polhemus_model_bit(id->model)) != 0);
    Match m = Match::none;
    if (config.product_id != 0 ? d.idProduct == config.product_id
                               : wanted_model && !id->needs_firmware) {
      m = Match::usable;
    } else if (wanted_model && id->needs_firmware) {
      m = Match::needs_firmware;
    } else if (id != nullptr) {
      m = Match::other;
    }
    if (m > best.match) best = Candidate{m, list[i], id, d.idProduct};
  }
  return best;
}

}  // namespace

Status LibusbByteStream::probe() { return search(false); }

Status LibusbByteStream::do_reopen() { return search(true); }

Status LibusbByteStream::search(bool open) {
  if (ctx_ == nullptr) return StatusCode::failed_precondition;
  close();
  arrived_ = false;
  rx_.clear();
  found_ = {};
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(ctx_, &list);
  if (count < 0) {
    last_error_ = static_cast<int>(count);
    report(Level::error, "USB: cannot list the devices (%s)",
           libusb_error_name(static_cast<int>(count)));
    return StatusCode::io_error;
  }
  const Candidate c = best_candidate(config_, list, count);
  const Match best = c.match;
  libusb_device* chosen = c.device;
  const PolhemusUsbId* chosen_id = c.id;
  const std::uint16_t chosen_product = c.product;
  Status result = StatusCode::unavailable;
  char where[64] = "";
  if (chosen != nullptr) {
    std::snprintf(where, sizeof where, "on bus %03u device %03u",
                  static_cast<unsigned>(libusb_get_bus_number(chosen)),
                  static_cast<unsigned>(libusb_get_device_address(chosen)));
  }
  const char* name = chosen_id != nullptr ? chosen_id->name : "a tracker";
  const unsigned vid = config_.vendor_id;
  const unsigned pid = chosen_product;
  switch (best) {
    case Match::none: {
      char wanted[320];
      describe_wanted(wanted, sizeof wanted);
      report(Level::warning, "USB: no tracker found; looked for %s; still looking", wanted);
      break;
    }
    case Match::other:
      if (chosen_id->model == PolhemusUsbModel::unsupported) {
        report(Level::error, "USB: found a Polhemus %s (%04x:%04x) %s: not supported (%s)", name,
               vid, pid, where, chosen_id->note);
      } else {
        char wanted[320];
        describe_wanted(wanted, sizeof wanted);
        report(Level::error,
               "USB: found a Polhemus %s (%04x:%04x) %s, but the station reads %s only "
               "(tracker.model): set it to this unit's model, or leave it out to detect the "
               "model at start, and restart",
               name, vid, pid, where, wanted);
      }
      result = StatusCode::io_error;
      break;
    case Match::needs_firmware:
      report(Level::error,
             "USB: found a Polhemus %s (%04x:%04x) %s still waiting for its firmware: install "
             "Debian's fxload (apt install fxload), put Polhemus' %s and a3load.hex in "
             "/usr/local/share/PolhemusUsb and the udev rule 99-twister.rules (twister-station's "
             "deploy/, in /lib/udev/rules.d), then replug the unit: it comes back as %04x:%04x",
             name, vid, pid, where, chosen_id->firmware, vid,
             static_cast<unsigned>(polhemus_running_id(chosen_id->model)));
      result = StatusCode::io_error;
      break;
    case Match::usable:
      found_.id = chosen_id;
      found_.product_id = chosen_product;
      found_.bus = libusb_get_bus_number(chosen);
      found_.address = libusb_get_device_address(chosen);
      result = open ? open_device(chosen) : ok_status();
      if (result.ok()) report(Level::info, "USB: found %s (%04x:%04x) %s", name, vid, pid, where);
      break;
  }
  libusb_free_device_list(list, 1);
  if (!result.ok() && best == Match::usable) found_ = {};
  return result;
}

// The configured endpoints, else the interface's first bulk IN and OUT.
bool LibusbByteStream::find_endpoints(libusb_device* device) {
  found_.endpoint_in = config_.endpoint_in;
  found_.endpoint_out = config_.endpoint_out;
  if (found_.endpoint_in != 0 && found_.endpoint_out != 0) return true;
  libusb_config_descriptor* cfg = nullptr;
  if (libusb_get_active_config_descriptor(device, &cfg) != 0) return false;
  for (int i = 0; i < cfg->bNumInterfaces; ++i) {
    const libusb_interface& itf = cfg->interface[i];
    if (itf.num_altsetting < 1 || itf.altsetting[0].bInterfaceNumber != config_.interface_number)
      continue;
    const libusb_interface_descriptor& alt = itf.altsetting[0];
    for (int e = 0; e < alt.bNumEndpoints; ++e) {
      const libusb_endpoint_descriptor& ep = alt.endpoint[e];
      if ((ep.bmAttributes & LIBUSB_TRANSFER_TYPE_MASK) != LIBUSB_TRANSFER_TYPE_BULK) continue;
      const bool in = (ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) != 0;
      std::uint8_t& slot = in ? found_.endpoint_in : found_.endpoint_out;
      if (slot == 0) slot = ep.bEndpointAddress;
    }
  }
  libusb_free_config_descriptor(cfg);
  return found_.endpoint_in != 0 && found_.endpoint_out != 0;
}

Status LibusbByteStream::open_device(libusb_device* device) {
  const char* name = found_.id != nullptr ? found_.id->name : "tracker";
  char where[96];
  std::snprintf(where, sizeof where, "%s (%04x:%04x) on bus %03u device %03u", name,
                static_cast<unsigned>(config_.vendor_id), static_cast<unsigned>(found_.product_id),
                static_cast<unsigned>(found_.bus), static_cast<unsigned>(found_.address));
  if (!find_endpoints(device)) {
    report(Level::error, "USB: found %s, but interface %u has no bulk IN and OUT endpoints", where,
           static_cast<unsigned>(config_.interface_number));
    return StatusCode::io_error;
  }
  if (const int rc = libusb_open(device, &handle_); rc != 0) {
    handle_ = nullptr;
    last_error_ = rc;
    report(
        Level::error, "USB: found %s, but cannot open it (%s%s)", where, libusb_error_name(rc),
        rc == LIBUSB_ERROR_ACCESS ? ": install the udev rule 99-twister.rules for its group" : "");
    return rc == LIBUSB_ERROR_NO_DEVICE ? StatusCode::unavailable : StatusCode::io_error;
  }
  libusb_set_auto_detach_kernel_driver(handle_, 1);
  if (const int rc = libusb_claim_interface(handle_, config_.interface_number); rc != 0) {
    last_error_ = rc;
    libusb_close(handle_);
    handle_ = nullptr;
    report(Level::error, "USB: found %s, but cannot claim interface %u (%s)", where,
           static_cast<unsigned>(config_.interface_number), libusb_error_name(rc));
    return StatusCode::io_error;
  }
  if (in_transfer_ == nullptr) {  // close() could not replace a stuck transfer
    libusb_release_interface(handle_, config_.interface_number);
    libusb_close(handle_);
    handle_ = nullptr;
    report(Level::error, "USB: found %s, but out of memory for its transfer", where);
    return StatusCode::resource_exhausted;
  }
  libusb_fill_bulk_transfer(in_transfer_, handle_, found_.endpoint_in, in_buffer_.data(),
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
  const std::size_t n = rx_.pop_front_into(dest);
  if (!in_flight_ && room_for_transfer()) {
    if (const int rc = libusb_submit_transfer(in_transfer_); rc != 0) return gone(rc);
    in_flight_ = true;
  }
  return n;
}

Result<std::size_t> LibusbByteStream::do_write(std::span<const std::byte> src) {
  if (handle_ == nullptr) return StatusCode::io_error;
  if (removed_) return gone(LIBUSB_ERROR_NO_DEVICE);
  int sent = 0;
  // libusb's API takes a non-const buffer for both directions; OUT does not write it.
  auto* data = const_cast<unsigned char*>(reinterpret_cast<const unsigned char*>(src.data()));
  const int rc = libusb_bulk_transfer(handle_, found_.endpoint_out, data,
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
