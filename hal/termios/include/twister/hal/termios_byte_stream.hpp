// TermiosByteStream: the ByteStream port on a POSIX serial device (RS-232, USB-serial
// bridge, or a PTY slave). Raw 8N1 at the configured baud, flow control per config,
// non-blocking: read() never waits. A hang-up (POLLHUP/POLLERR or EIO, never a bare
// read() == 0) closes the port and returns io_error ("disconnected"); reopen() opens
// the same path again, so a symlink that the simulator or udev moves atomically on
// re-plug is followed. As a PollSource it asks to wait for input on its descriptor
// while open (none while closed). Not thread-safe.
#pragma once

#include <string>

#include "twister/hal/poll_source.hpp"
#include "twister/ports/byte_stream.hpp"

namespace twister::hal {

enum class FlowControl { none, rts_cts, xon_xoff };

struct TermiosConfig {
  std::string path;                      // e.g. /dev/ttyUSB0, /dev/serial/by-id/..., a symlink
  int baud = 115200;                     // 2400 ... 115200 (and higher where supported)
  FlowControl flow = FlowControl::none;  // the Fastrak runs without flow control
};

class TermiosByteStream final : public ports::ByteStream, public PollSource {
 public:
  using ports::ByteStream::reopen;  // the same as PollSource::reopen()

  explicit TermiosByteStream(TermiosConfig config);
  ~TermiosByteStream() override;
  TermiosByteStream(const TermiosByteStream&) = delete;
  TermiosByteStream& operator=(const TermiosByteStream&) = delete;

  bool is_open() const { return fd_ >= 0; }
  // errno of the last failure (0 if none), logged once by the caller.
  int last_errno() const { return last_errno_; }
  void close();

 private:
  Result<std::size_t> do_read(std::span<std::byte> dest) override;
  Result<std::size_t> do_write(std::span<const std::byte> src) override;
  Status do_reopen() override;
  void do_discard_input() override;
  std::size_t do_poll_fds(std::span<pollfd> out) const override;
  Status disconnected(int err);

  TermiosConfig config_;
  int fd_ = -1;
  int last_errno_ = 0;
};

// The termios speed constant for a baud rate; false if unsupported.
bool baud_to_speed(int baud, unsigned& speed);

}  // namespace twister::hal
