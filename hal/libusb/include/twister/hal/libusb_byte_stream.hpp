// LibusbByteStream: the ByteStream port over a Polhemus tracker's USB interface
// (same command set as RS-232, carried on bulk endpoints). Vendor/product id,
// interface and endpoints come from the config. One bulk IN transfer is always in
// flight (asynchronous); read() runs libusb's event handling without waiting and
// copies what has arrived. write() is a bulk OUT transfer bounded by timeout_ms
// (commands are a few bytes). Hot-plug: where libusb supports it, arrival and removal
// of the configured device are reported by callbacks; removal makes the next read()
// / write() fail with io_error at once (without hot-plug, the first failing transfer
// reports it: LIBUSB_ERROR_NO_DEVICE). reopen() finds the device again.
// Errors: init() -> io_error (libusb_init failed), invalid_argument (endpoint
// directions wrong); reopen() -> unavailable (not plugged in), io_error (cannot open or
// claim: permissions, interface busy); read()/write() -> io_error (gone).
// PollSource: while the device is open, libusb's descriptors with the events libusb
// asks for (kept current by libusb's pollfd notifiers, so poll_fds() neither calls
// into libusb nor allocates); none while closed, when nothing would handle their
// events (the session's retry timer paces a re-plug).
// Not thread-safe: one owner (the station loop) calls everything.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/inline_ring.hpp"
#include "twister/base/inline_vector.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/byte_stream.hpp"

struct libusb_context;
struct libusb_device_handle;
struct libusb_transfer;

namespace twister::hal {

struct LibusbConfig {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::uint8_t interface_number = 0;
  std::uint8_t endpoint_in = 0x81;   // bit 7 set
  std::uint8_t endpoint_out = 0x01;  // bit 7 clear
  unsigned timeout_ms = 100;         // per bulk OUT transfer
};

class LibusbByteStream final : public ports::ByteStream, public PollSource {
 public:
  using ports::ByteStream::reopen;  // the same as PollSource::reopen()

  explicit LibusbByteStream(const LibusbConfig& config) : config_(config) {}
  ~LibusbByteStream() override;
  LibusbByteStream(const LibusbByteStream&) = delete;
  LibusbByteStream& operator=(const LibusbByteStream&) = delete;

  // Creates the libusb context and registers the hot-plug callbacks. Call once.
  Status init();
  bool hotplug_supported() const { return hotplug_; }
  // Hot-plug said the device arrived since the last reopen() (a hint to retry now).
  bool arrival_pending() const { return arrived_; }
  bool is_open() const { return handle_ != nullptr; }
  // The last LIBUSB_ERROR_* (0 if none), logged once by the caller.
  int last_error() const { return last_error_; }
  void close();

 private:
  static constexpr std::size_t kRxBytes = 4096;  // ring of received bytes
  static constexpr std::size_t kTransferBytes = 512;

  Result<std::size_t> do_read(std::span<std::byte> dest) override;
  Result<std::size_t> do_write(std::span<const std::byte> src) override;
  Status do_reopen() override;
  void do_discard_input() override;
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  void pump_events();
  void add_fd(int fd, short events);
  void remove_fd(int fd);
  Status gone(int error);
  friend struct LibusbCallbacks;  // libusb's C callbacks (defined in the .cpp)

  LibusbConfig config_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  libusb_transfer* in_transfer_ = nullptr;
  bool in_flight_ = false;
  bool hotplug_ = false;
  bool arrived_ = false;
  bool removed_ = false;
  int last_error_ = 0;
  std::array<std::uint8_t, kTransferBytes> in_buffer_{};
  InlineRing<std::byte, kRxBytes> rx_;  // received, not read yet
  std::uint64_t rx_dropped_ = 0;        // ring full: oldest bytes kept, newest dropped
  InlineVector<pollfd, PollSource::kMaxFds> usb_fds_;  // libusb's descriptors
};

}  // namespace twister::hal
