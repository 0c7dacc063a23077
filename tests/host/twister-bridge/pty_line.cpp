// pty_line: a serial line between two programs for the display-link tests. Opens
// two PTY pairs, prints their slave paths ("A=/dev/pts/N", "B=/dev/pts/M") and
// relays bytes between the two masters in both directions at the pace of a UART
// (8N1: baud / 10 bytes per second, a 16-byte FIFO of burst), until SIGTERM or
// SIGINT. A PTY by itself moves bytes at memory speed whatever baud rate termios
// is given; this makes the test's 230 400 baud real. On exit it prints, per
// direction, the bytes relayed and the busiest second (stderr).
// Usage: pty_line BAUD
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

volatile sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

double now_s() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) / 1e9;
}

struct Pty {
  int master = -1;
  int held_slave = -1;  // kept open so the master never reads a hang-up
  std::string name;     // ptsname()'s buffer is static: copied
};

bool open_pty(Pty& p) {
  p.master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (p.master < 0 || ::grantpt(p.master) != 0 || ::unlockpt(p.master) != 0) return false;
  p.name = ::ptsname(p.master);
  termios tio{};
  ::tcgetattr(p.master, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(p.master, TCSANOW, &tio);
  p.held_slave = ::open(p.name.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (p.held_slave < 0) return false;
  ::tcgetattr(p.held_slave, &tio);
  ::cfmakeraw(&tio);
  ::tcsetattr(p.held_slave, TCSANOW, &tio);
  return true;
}

// One direction of the line: bytes read from `from` wait in `pending` and leave
// for `to` as the UART's pace allows.
struct Direction {
  int from = -1;
  int to = -1;
  double tokens = 0.0;
  std::vector<char> pending;
  unsigned long long total = 0;
  unsigned long long window = 0;
  unsigned long long busiest = 0;
};

void pump(Direction& d, double bytes_per_s, double dt) {
  d.tokens = std::min(d.tokens + dt * bytes_per_s, 16.0);
  if (d.pending.empty()) {
    char buf[4096];
    const ssize_t n = ::read(d.from, buf, sizeof buf);
    if (n > 0) d.pending.assign(buf, buf + n);
  }
  const auto allowed = static_cast<std::size_t>(d.tokens);
  const std::size_t take = std::min(allowed, d.pending.size());
  if (take == 0) return;
  const ssize_t w = ::write(d.to, d.pending.data(), take);
  if (w <= 0) return;
  d.pending.erase(d.pending.begin(), d.pending.begin() + w);
  d.tokens -= static_cast<double>(w);
  d.total += static_cast<unsigned long long>(w);
  d.window += static_cast<unsigned long long>(w);
}

}  // namespace

int main(int argc, char** argv) {
  const int baud = argc > 1 ? std::atoi(argv[1]) : 230400;
  if (baud <= 0) return 2;
  Pty a;
  Pty b;
  if (!open_pty(a) || !open_pty(b)) {
    std::perror("pty_line");
    return 1;
  }
  std::printf("A=%s\nB=%s\n", a.name.c_str(), b.name.c_str());
  std::fflush(stdout);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  ::sigaction(SIGTERM, &sa, nullptr);
  ::sigaction(SIGINT, &sa, nullptr);
  Direction ab;
  ab.from = a.master;
  ab.to = b.master;
  Direction ba;
  ba.from = b.master;
  ba.to = a.master;
  const double rate = baud / 10.0;
  double last = now_s();
  double window_start = last;
  while (g_stop == 0) {
    pollfd fds[2] = {{a.master, POLLIN, 0}, {b.master, POLLIN, 0}};
    ::poll(fds, 2, 1);
    const double t = now_s();
    pump(ab, rate, t - last);
    pump(ba, rate, t - last);
    last = t;
    if (t - window_start >= 1.0) {
      for (Direction* d : {&ab, &ba}) {
        d->busiest = std::max(d->busiest, d->window);
        d->window = 0;
      }
      window_start = t;
    }
  }
  std::fprintf(stderr,
               "pty_line: A->B %llu bytes (busiest second %llu), B->A %llu bytes (busiest %llu); "
               "capacity %d bytes/s\n",
               ab.total, ab.busiest, ba.total, ba.busiest, baud / 10);
  return 0;
}
