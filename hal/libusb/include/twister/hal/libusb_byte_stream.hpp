// LibusbByteStream: the ByteStream port over a Polhemus tracker's USB interface
// (same command set as RS-232, carried on bulk endpoints). Which device: a
// vendor/product id from the config, or (product_id 0) any Polhemus tracker of the
// wanted models by its product id (polhemus_usb.hpp); interface from the config;
// endpoints from the config or else the interface's first bulk OUT and IN (VRPN's
// Liberty drivers use 0x04 / 0x88). One bulk IN transfer is in flight (asynchronous)
// whenever the receive ring has room for all it may bring (back-pressure: otherwise the
// unit keeps its data until read() makes room); read() runs libusb's event handling
// without waiting and copies what has arrived. write() is a bulk OUT transfer bounded by timeout_ms
// (commands are a few bytes). Hot-plug: where libusb supports it, arrival and removal of a matching
// device are reported by callbacks; removal makes the next read() / write() fail with
// io_error at once (without hot-plug, the first failing transfer reports it:
// LIBUSB_ERROR_NO_DEVICE); an arrival while closed makes device_arrived() true, so
// the tracker session reopens at once. reopen() searches again.
// DeviceReport: every search leaves one line saying which tracker was found where,
// what was looked for and not found, a unit still waiting for its firmware (with the
// fix: fxload and the udev rule), or a Polhemus unit of another model.
// Errors: init() -> io_error (libusb_init failed), invalid_argument (endpoint
// directions wrong); reopen() -> unavailable (not plugged in), io_error (cannot open or
// claim: permissions, interface busy; no firmware yet; another model);
// read()/write() -> io_error (gone).
// PollSource: while the device is open, libusb's descriptors with the events libusb
// asks for (kept current by libusb's pollfd notifiers, so poll_fds() neither calls
// into libusb nor allocates); none while closed, when nothing would handle their
// events (the session's retry timer and device_arrived() pace a re-plug).
// Not thread-safe: one owner (the station loop) calls everything.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/inline_ring.hpp"
#include "twister/base/inline_vector.hpp"
#include "twister/hal/device_report.hpp"
#include "twister/hal/polhemus_usb.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/ports/byte_stream.hpp"

struct libusb_context;
struct libusb_device;
struct libusb_device_handle;
struct libusb_transfer;

namespace twister::hal {

struct LibusbConfig {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;  // 0: any Polhemus tracker of `models` (vendor 0x0f44)
  std::uint8_t models = kAnyReadablePolhemus;  // polhemus_model_bit() mask, product_id 0
  std::uint8_t interface_number = 0;
  std::uint8_t endpoint_in = 0;   // bit 7 set; 0: the interface's first bulk IN
  std::uint8_t endpoint_out = 0;  // bit 7 clear; 0: the interface's first bulk OUT
  unsigned timeout_ms = 100;      // per bulk OUT transfer
};

// Where the last search found a tracker (valid while found() is true).
struct UsbTrackerFound {
  const PolhemusUsbId* id = nullptr;  // nullptr: not in the Polhemus table (explicit ids)
  std::uint16_t product_id = 0;
  std::uint8_t bus = 0;
  std::uint8_t address = 0;
  std::uint8_t endpoint_in = 0;  // after reopen(): the endpoints in use
  std::uint8_t endpoint_out = 0;
};

class LibusbByteStream final : public ports::ByteStream, public PollSource, public DeviceReport {
 public:
  using ports::ByteStream::reopen;  // the same as PollSource::reopen()

  explicit LibusbByteStream(const LibusbConfig& config) : config_(config) {}
  ~LibusbByteStream() override;
  LibusbByteStream(const LibusbByteStream&) = delete;
  LibusbByteStream& operator=(const LibusbByteStream&) = delete;

  // Creates the libusb context and registers the hot-plug callbacks. Call once.
  Status init();
  // Searches as reopen() does and reports, without opening anything (the station's
  // model detection at start). ok: a readable tracker of a wanted model is there
  // (found()); else reopen()'s codes.
  Status probe();
  // The tracker the last search found usable (probe() or reopen() ok), else nullptr.
  const UsbTrackerFound* found() const { return found_.product_id != 0 ? &found_ : nullptr; }
  bool hotplug_supported() const { return hotplug_; }
  // Hot-plug said the device arrived since the last reopen() (a hint to retry now).
  bool arrival_pending() const { return arrived_; }
  bool is_open() const { return handle_ != nullptr; }
  // The last LIBUSB_ERROR_* (0 if none), logged once by the caller.
  int last_error() const { return last_error_; }
  void close();

  // DeviceReport
  std::uint32_t changes() const override { return report_.changes; }
  const char* text() const override { return report_.text.data(); }
  Level level() const override { return report_.level; }

 private:
  static constexpr std::size_t kRxBytes = 4096;  // ring of received bytes
  static constexpr std::size_t kTransferBytes = 512;

  Result<std::size_t> do_read(std::span<std::byte> dest) override;
  Result<std::size_t> do_write(std::span<const std::byte> src) override;
  Status do_reopen() override;
  void do_discard_input() override;
  bool do_device_arrived() override;
  // The search of probe() and reopen(); opens the device found when `open`.
  Status search(bool open);
  Status open_device(libusb_device* device);
  bool find_endpoints(libusb_device* device);
  void report(Level level, const char* format, ...) __attribute__((format(printf, 3, 4)));
  // "FASTRAK (0f44:0002), ..." : what a search looks for.
  void describe_wanted(char* out, std::size_t size) const;
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  void pump_events();
  bool room_for_transfer() const { return rx_.max_size() - rx_.size() >= kTransferBytes; }
  void add_fd(int fd, short events);
  void remove_fd(int fd);
  Status gone(int error);
  friend struct LibusbCallbacks;  // libusb's C callbacks (defined in the .cpp)

  LibusbConfig config_;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  libusb_transfer* in_transfer_ = nullptr;
  bool in_flight_ = false;
  bool closing_ = false;  // close() is cancelling the IN transfer: no resubmission
  bool hotplug_ = false;
  bool arrived_ = false;
  bool removed_ = false;
  int last_error_ = 0;
  std::array<std::uint8_t, kTransferBytes> in_buffer_{};
  InlineRing<std::byte, kRxBytes> rx_;  // received, not read yet
  std::uint64_t rx_dropped_ = 0;  // ring full: oldest kept, newest dropped (never: back-pressure)
  InlineVector<pollfd, PollSource::kMaxFds> usb_fds_;  // libusb's descriptors
  UsbTrackerFound found_{};
  struct Report {
    std::array<char, 512> text{};
    Level level = Level::info;
    std::uint32_t changes = 0;
  } report_;
};

}  // namespace twister::hal
