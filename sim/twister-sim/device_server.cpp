// PTY facts used here: docs/fastrak.md "Pseudo-terminal facts" (raw mode, hang-up
// seen as POLLHUP by the reader, the /dev/pts node vanishing, symlink via rename()).
#include "device_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace twister::sim {
namespace {
constexpr std::size_t kMaxBacklog = 1 << 16;

hal::Error io_error(std::string message) {
  return hal::make_error(StatusCode::io_error, std::move(message));
}

// The bits/s of a termios speed code; 0 when it is none of the standard rates.
int speed_to_baud(speed_t speed) {
  static constexpr int kRates[] = {300,    600,    1200,   2400,    4800,    9600,
                                   19200,  38400,  57600,  115200,  230400,  460800,
                                   500000, 576000, 921600, 1000000, 2000000, 4000000};
  for (const int rate : kRates) {
    unsigned code = 0;
    if (hal::baud_to_speed(rate, code) && code == speed) return rate;
  }
  return 0;
}

bool is_symlink(const std::string& path) {
  struct stat st {};
  return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

bool absent_or_symlink(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return errno == ENOENT;
  return S_ISLNK(st.st_mode);
}
}  // namespace

DeviceServer::DeviceServer(FastrakDevice& device, ServeOptions options)
    : device_(device), options_(std::move(options)), epoch_(std::chrono::steady_clock::now()) {}

DeviceServer::~DeviceServer() { close_pty(); }

std::int64_t DeviceServer::now_us() const {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() -
                                                               epoch_)
      .count();
}

hal::Expected<void> DeviceServer::open_pty() {
  const int m = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (m < 0 || ::grantpt(m) != 0 || ::unlockpt(m) != 0) {
    hal::Error error = io_error(std::string("cannot create a PTY: ") + std::strerror(errno));
    if (m >= 0) ::close(m);
    return error;
  }
  const char* name = ::ptsname(m);
  if (name == nullptr) {
    ::close(m);
    return io_error("ptsname failed");
  }
  termios tio{};
  if (::tcgetattr(m, &tio) == 0) {
    ::cfmakeraw(&tio);
    ::tcsetattr(m, TCSANOW, &tio);
  }
  slave_path_ = name;
  slave_keep_ = ::open(name, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  master_ = m;
  ++counters_.ptys_opened;
  if (!options_.link.empty()) {
    // Only a symbolic link (ours, from an earlier PTY or run) is ever replaced or
    // removed at the link path: never a file someone else made (a journal, say).
    const std::string tmp = options_.link + ".tmp";
    if (!absent_or_symlink(options_.link) || !absent_or_symlink(tmp)) {
      return io_error("cannot link " + options_.link + ": it (or " + tmp +
                      ") exists and is not a symbolic link; left untouched");
    }
    // New name first, then an atomic rename: readers never see a missing link.
    ::unlink(tmp.c_str());
    if (::symlink(name, tmp.c_str()) != 0 || ::rename(tmp.c_str(), options_.link.c_str()) != 0) {
      return io_error("cannot link " + options_.link + ": " + std::strerror(errno));
    }
  }
  return {};
}

void DeviceServer::close_pty() {
  if (slave_keep_ >= 0) ::close(slave_keep_);
  if (master_ >= 0) ::close(master_);
  slave_keep_ = master_ = -1;
}

hal::Expected<void> DeviceServer::start() {
  if (options_.device.empty()) return open_pty();
  tty_ = std::make_unique<hal::TermiosByteStream>(
      hal::TermiosConfig{options_.device, options_.baud, hal::FlowControl::none});
  const Status s = tty_->reopen();
  if (!s.ok()) {
    return io_error("cannot open " + options_.device + ": " + std::strerror(tty_->last_errno()));
  }
  slave_path_ = options_.device;
  return {};
}

hal::Expected<void> DeviceServer::step(int wait_ms) {
  const std::int64_t now = now_us();
  std::array<std::byte, 512> in{};
  if (tty_) {
    // HIL: a real line cannot hang up from here; the device just goes quiet.
    if (device_.hung_up(now)) {
      out_.clear();
    } else {
      auto n = tty_->read(in);
      if (!n.ok()) return io_error("serial device failed");
      counters_.bytes_in += *n;
      device_.receive(in.data(), *n, now);
      device_.advance(now, out_);
      if (!out_.empty()) {
        auto w = tty_->write(out_);
        if (w.ok()) {
          counters_.bytes_out += *w;
          out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(*w));
        }
      }
    }
    ::usleep(static_cast<useconds_t>(wait_ms) * 1000u);
    return {};
  }

  if (hang_up_pty(wait_ms)) return {};
  if (master_ < 0) {
    if (hal::Expected<void> opened = open_pty(); !opened) return opened;
  }
  check_host_baud();

  for (;;) {
    const ssize_t n = ::read(master_, in.data(), in.size());
    if (n <= 0) break;  // EAGAIN, or EIO while no client holds the slave
    counters_.bytes_in += static_cast<std::uint64_t>(n);
    device_.receive(in.data(), static_cast<std::size_t>(n), now);
  }
  device_.advance(now, out_);
  if (!out_.empty()) {
    const ssize_t w = ::write(master_, out_.data(), out_.size());
    if (w > 0) {
      counters_.bytes_out += static_cast<std::uint64_t>(w);
      out_.erase(out_.begin(), out_.begin() + w);
    }
    if (out_.size() > kMaxBacklog) {
      counters_.overflow_dropped += out_.size();
      out_.clear();
    }
  }
  pollfd p{master_, POLLIN, 0};
  ::poll(&p, 1, wait_ms);
  return {};
}

void DeviceServer::check_host_baud() {
  // The master shares the slave's termios: the speed the host set on its side.
  termios tio{};
  if (::tcgetattr(master_, &tio) != 0) return;
  counters_.host_baud = speed_to_baud(::cfgetospeed(&tio));
  device_.set_host_baud(counters_.host_baud);
}

bool DeviceServer::hang_up_pty(int wait_ms) {
  if (!device_.hung_up(now_us())) return false;
  if (options_.port == PortKind::fixed) {
    // A fixed UART stays: no hang-up for the reader, the line is just dead. What the
    // host sends meanwhile reaches nobody.
    if (master_ >= 0) {
      std::array<std::byte, 512> in{};
      while (::read(master_, in.data(), in.size()) > 0) {
      }
    }
    out_.clear();
  } else if (master_ >= 0) {
    // Unplugged: the link goes first (as udev removes by-id links), because the
    // /dev/pts number is reused by the next PTY anyone opens and a stale link would
    // lead the reader to somebody else's line. Then the reader sees POLLHUP.
    if (!options_.link.empty() && is_symlink(options_.link)) ::unlink(options_.link.c_str());
    close_pty();
    ++counters_.hangups;
    out_.clear();
  }
  ::usleep(static_cast<useconds_t>(wait_ms) * 1000u);
  return true;
}

}  // namespace twister::sim
