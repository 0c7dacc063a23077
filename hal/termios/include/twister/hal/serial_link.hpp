// SerialLink: ports::LinkPort over a tty (termios, raw 8N1): the display link on a
// serial line or a USB CDC ACM device (/dev/ttyACM0, a udev symlink), beside the
// sockets. One far end, always "connected" while the device is open: a restarted
// peer is recognised by its hello (the framing resyncs at the next 0x00). An
// unplugged or failed device reads as no peer (unavailable) and is reopened at most
// every reopen_interval_ms, never blocking. PollSource: the tty's descriptor.
#pragma once

#include <cstdint>
#include <string>

#include "twister/hal/expected.hpp"
#include "twister/hal/poll_source.hpp"
#include "twister/hal/termios_byte_stream.hpp"
#include "twister/ports/link_port.hpp"

namespace twister::hal {

struct SerialLinkConfig {
  std::string path;                      // e.g. /dev/twister-display, /dev/ttyACM0
  int baud = 230400;                     // any rate baud_to_speed() knows
  FlowControl flow = FlowControl::none;  // USB CDC ignores it; a real UART may want rtscts
  std::uint32_t reopen_interval_ms = 500;
};

class SerialLink final : public ports::LinkPort, public PollSource {
 public:
  explicit SerialLink(const SerialLinkConfig& config);

  // Opens the device now. invalid_argument: unsupported baud rate; unavailable:
  // not there (yet: it is retried on use); io_error: present but not usable.
  Expected<void> open();
  bool is_open() const { return tty_.is_open(); }
  int last_errno() const { return tty_.last_errno(); }

 private:
  Result<std::size_t> do_send(std::span<const std::byte> src) override;
  Result<std::size_t> do_receive(std::span<std::byte> dest) override;
  std::size_t do_poll_fds(std::span<pollfd> out) const override { return tty_.poll_fds(out); }
  Status do_reopen() override;
  bool ensure_open();

  SerialLinkConfig config_;
  TermiosByteStream tty_;
  std::int64_t next_attempt_ms_ = 0;
};

}  // namespace twister::hal
