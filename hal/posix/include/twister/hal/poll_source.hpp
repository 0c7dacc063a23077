// PollSource: what every backend offers the station's event loop, whatever it
// wraps: the descriptors to wait on in poll(2) (fd and events) and a way to reopen
// its device after it failed. Implemented by each backend (termios, libusb, gpiod,
// hidapi, socket link, the in-process simulator); a device that offers no
// descriptor (hidapi, the simulator) returns none and the loop's timeout paces it.
// poll_fds() runs on every pass of the loop: it never blocks or allocates.
// A backend that is also a ports::ByteStream reopens the same way through both
// interfaces (one do_reopen() overrides both).
#pragma once

#include <poll.h>

#include <cstddef>
#include <span>

#include "twister/base/status.hpp"

namespace twister::hal {

class PollSource {
 public:
  // The most descriptors one source asks for (gpiod: one per line, libusb: a few).
  static constexpr std::size_t kMaxFds = 8;

  virtual ~PollSource() = default;

  // Writes the descriptors to wait on now into `out` (fd and events; revents 0)
  // and returns how many, at most out.size(). 0: nothing to wait on now (closed,
  // or the device offers no descriptor).
  std::size_t poll_fds(std::span<pollfd> out) const { return do_poll_fds(out); }

  // Reopens the device with its configured settings (after an io_error).
  // unavailable: not present (yet, unplugged); io_error: present but it cannot be
  // opened; failed_precondition: never configured.
  Status reopen() { return do_reopen(); }

 private:
  virtual std::size_t do_poll_fds(std::span<pollfd> out) const = 0;
  virtual Status do_reopen() = 0;
};

}  // namespace twister::hal
