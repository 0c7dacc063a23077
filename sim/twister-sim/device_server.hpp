// DeviceServer: serves a FastrakDevice on a fresh PTY (printing/linking the slave
// path), or on a real serial device for hardware-in-the-loop rigs. On a PTY it reads
// the host's configured speed from the master (tcgetattr) and tells the device, which
// garbles the line at a mismatch. A hang-up fault behind a USB-serial adapter
// removes the link and closes the PTY (the node vanishes), then creates a new pair and
// moves the symlink atomically with rename(); behind a fixed port (/dev/ttyS*) the
// node and link stay and the line just goes dead. Paced in real time from a steady
// clock; one thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/hal/termios_byte_stream.hpp"
#include "twister/sim/fastrak_device.hpp"

namespace twister::sim {

// What the host's port is: a USB-serial adapter (the tty and its by-id link vanish
// when the unit is unplugged or powered off) or a fixed UART port (it stays).
enum class PortKind : std::uint8_t { usb_adapter, fixed };

struct ServeOptions {
  std::string link;    // PTY mode: stable symlink to the current slave (optional)
  std::string device;  // HIL mode: a real tty path instead of a PTY
  int baud = 115200;   // HIL mode line rate
  PortKind port = PortKind::usb_adapter;  // PTY mode: what a hang-up looks like
};

struct ServeCounters {
  std::uint64_t ptys_opened = 0;
  std::uint64_t hangups = 0;
  std::uint64_t bytes_in = 0;
  std::uint64_t bytes_out = 0;
  std::uint64_t overflow_dropped = 0;  // output dropped because nobody read it
  int host_baud = 0;                   // PTY mode: the slave's speed last read (0: unknown)
};

class DeviceServer {
 public:
  // The device's time origin is the moment of construction.
  DeviceServer(FastrakDevice& device, ServeOptions options);
  ~DeviceServer();
  DeviceServer(const DeviceServer&) = delete;
  DeviceServer& operator=(const DeviceServer&) = delete;

  // Opens the first PTY (or the HIL device). Error io_error (no PTY, the link or the
  // device cannot be made or opened) with the reason.
  hal::Expected<void> start();
  // One iteration: moves bytes both ways, waiting up to wait_ms for input.
  // Error io_error on a fatal failure (the serial device, a new PTY after a hang-up).
  hal::Expected<void> step(int wait_ms);
  // Microseconds since construction (the device's clock).
  std::int64_t now_us() const;

  const std::string& slave_path() const { return slave_path_; }
  const ServeCounters& counters() const { return counters_; }

 private:
  hal::Expected<void> open_pty();
  void close_pty();
  // PTY mode: the hang-up of the unit behind this port; true while it lasts.
  bool hang_up_pty(int wait_ms);
  // PTY mode: reads the slave's configured speed and hands it to the device.
  void check_host_baud();

  FastrakDevice& device_;
  ServeOptions options_;
  std::chrono::steady_clock::time_point epoch_;
  int master_ = -1;
  int slave_keep_ = -1;  // keeps the line up while the client is between opens
  std::unique_ptr<hal::TermiosByteStream> tty_;
  std::string slave_path_;
  std::vector<std::byte> out_;
  ServeCounters counters_;
};

}  // namespace twister::sim
