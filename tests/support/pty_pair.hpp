// Test helper: a PTY pair (raw master) whose master side plays the device or the host
// (termios backend tests, twister-sim's HIL mode).
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <string>

namespace twister::test {

struct PtyPair {
  int master = -1;
  std::string slave;

  PtyPair() {
    master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;
    slave = ::ptsname(master);
    termios tio{};
    ::tcgetattr(master, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(master, TCSANOW, &tio);
  }
  ~PtyPair() { hang_up(); }
  void hang_up() {
    if (master >= 0) ::close(master);
    master = -1;
  }
  void write(const std::string& s) const { (void)!::write(master, s.data(), s.size()); }

  // Waits (up to timeout_ms) until the slave side's input queue holds at least n
  // bytes: the PTY hands written bytes to the line discipline asynchronously, so a
  // test must not assume they are there when write() returns. Blocks in poll() until
  // the first byte is readable; the rest of one write follows within microseconds.
  bool wait_slave_pending(int n, int timeout_ms = 5000) const {
    const int fd = ::open(slave.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) return false;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    bool ok = false;
    for (;;) {
      int pending = 0;
      if (::ioctl(fd, FIONREAD, &pending) == 0 && pending >= n) {
        ok = true;
        break;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) > 0 && pending > 0) ::sched_yield();
    }
    ::close(fd);
    return ok;
  }
  std::string read_all(int wait_ms = 50) const {
    std::string out;
    pollfd p{master, POLLIN, 0};
    while (::poll(&p, 1, wait_ms) > 0) {
      char buf[256];
      const ssize_t n = ::read(master, buf, sizeof buf);
      if (n <= 0) break;
      out.append(buf, static_cast<std::size_t>(n));
    }
    return out;
  }
};

}  // namespace twister::test
