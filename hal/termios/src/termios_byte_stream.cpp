// termios backend. Disconnection is decided from POLLHUP/POLLERR/EIO only: with
// VMIN = VTIME = 0 a read() of 0 just means "nothing yet".
#include "twister/hal/termios_byte_stream.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

namespace twister::hal {

bool baud_to_speed(int baud, unsigned& speed) {
  switch (baud) {
    case 2400:
      speed = B2400;
      return true;
    case 4800:
      speed = B4800;
      return true;
    case 9600:
      speed = B9600;
      return true;
    case 19200:
      speed = B19200;
      return true;
    case 38400:
      speed = B38400;
      return true;
    case 57600:
      speed = B57600;
      return true;
    case 115200:
      speed = B115200;
      return true;
    case 230400:
      speed = B230400;
      return true;
    case 460800:
      speed = B460800;
      return true;
    case 921600:
      speed = B921600;
      return true;
    default:
      return false;
  }
}

TermiosByteStream::TermiosByteStream(TermiosConfig config) : config_(std::move(config)) {}

TermiosByteStream::~TermiosByteStream() { close(); }

void TermiosByteStream::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Status TermiosByteStream::disconnected(int err) {
  last_errno_ = err;
  close();
  return StatusCode::io_error;
}

Status TermiosByteStream::do_reopen() {
  close();
  unsigned speed = 0;
  if (!baud_to_speed(config_.baud, speed)) return StatusCode::invalid_argument;
  const int fd = ::open(config_.path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    last_errno_ = errno;
    // Not there (yet): unplugged, or the simulator is between PTYs.
    if (errno == ENOENT || errno == ENXIO || errno == ENODEV || errno == EIO) {
      return StatusCode::unavailable;
    }
    return StatusCode::io_error;
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    last_errno_ = errno;
    ::close(fd);
    return StatusCode::io_error;
  }
  ::cfmakeraw(&tio);  // also clears PARMRK, so 0xFF is not doubled
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  tio.c_cflag |= CS8 | CLOCAL | CREAD;
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  if (config_.flow == FlowControl::rts_cts) tio.c_cflag |= CRTSCTS;
  if (config_.flow == FlowControl::xon_xoff) tio.c_iflag |= IXON | IXOFF;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  ::cfsetispeed(&tio, static_cast<speed_t>(speed));
  ::cfsetospeed(&tio, static_cast<speed_t>(speed));
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    last_errno_ = errno;
    ::close(fd);
    return StatusCode::io_error;
  }
  ::tcflush(fd, TCIOFLUSH);  // stale input from before the (re)open
  fd_ = fd;
  last_errno_ = 0;
  return ok_status();
}

Result<std::size_t> TermiosByteStream::do_read(std::span<std::byte> dest) {
  if (fd_ < 0) return StatusCode::io_error;
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, 0);
  if (r < 0) {
    if (errno == EINTR) return std::size_t{0};
    return disconnected(errno);
  }
  if (r == 0) return std::size_t{0};
  if ((p.revents & POLLIN) == 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
    return disconnected(EIO);
  }
  const ssize_t n = ::read(fd_, dest.data(), dest.size());
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return std::size_t{0};
    return disconnected(errno);
  }
  if (n == 0 && (p.revents & (POLLHUP | POLLERR)) != 0) return disconnected(EIO);
  return static_cast<std::size_t>(n);
}

Result<std::size_t> TermiosByteStream::do_write(std::span<const std::byte> src) {
  if (fd_ < 0) return StatusCode::io_error;
  const ssize_t n = ::write(fd_, src.data(), src.size());
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return std::size_t{0};
    return disconnected(errno);
  }
  return static_cast<std::size_t>(n);
}

void TermiosByteStream::do_discard_input() {
  if (fd_ >= 0) ::tcflush(fd_, TCIFLUSH);
}

std::size_t TermiosByteStream::do_poll_fds(std::span<pollfd> out) const {
  if (fd_ < 0 || out.empty()) return 0;
  out[0] = {fd_, POLLIN, 0};
  return 1;
}

}  // namespace twister::hal
