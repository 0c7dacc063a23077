// SimFastrakStream: the ByteStream port over an in-process FastrakDevice.
// Writes go to the device as commands; reads return the bytes whose transmission
// has completed by clock.now_us() (the model paces itself at baud/10 bytes per
// second and 120 Hz shared by the receivers). A scenario "hangup" fault looks like
// an unplugged USB-serial adapter: read/write fail with io_error and reopen() is
// unavailable until the fault ends; the unit behind it kept its configuration and streams on
// (issue 22: a pulled adapter does not power-cycle the unit).
// Steady state (reads while streaming) uses no heap: bytes go from the model's
// fixed line queue straight into the reader's buffer. Commands (start-up) may.
// PollSource: no descriptor (the loop's clock paces it); reopen() is the stream's.
#pragma once

#include <cstddef>

#include "twister/hal/poll_source.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/sim/fastrak_device.hpp"

namespace twister::sim {

class SimFastrakStream final : public ports::ByteStream, public hal::PollSource {
 public:
  using ports::ByteStream::reopen;  // the same as PollSource::reopen()

  // clock must outlive the stream. The device starts powered up at clock.now_us().
  SimFastrakStream(ports::Clock& clock, const FastrakDeviceConfig& config, Scenario scenario);

  const FastrakDevice& device() const { return device_; }
  bool connected() const { return connected_; }

 private:
  Result<std::size_t> do_read(std::span<std::byte> dest) override;
  Result<std::size_t> do_write(std::span<const std::byte> src) override;
  Status do_reopen() override;
  void do_discard_input() override;
  std::size_t do_poll_fds(std::span<pollfd>) const override { return 0; }

  ports::Clock& clock_;
  FastrakDevice device_;
  bool connected_ = false;
};

}  // namespace twister::sim
