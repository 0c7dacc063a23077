// Test rig for real-time tests of twister-sim's server on a PTY: the DeviceServer in
// its own thread (stopped and joined even when an assertion returns early), and a
// raw termios client on the link that sets its own line speed and waits on poll(2)
// for bytes, never sleeping.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include "device_server.hpp"
#include "support/poll_wait.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim::test_rig {

inline Scenario scenario(const std::string& text) {
  Scenario sc;
  std::string err;
  if (!parse_scenario(text, sc, err)) ADD_FAILURE() << err;
  return sc;
}

inline std::string link_path(const char* name) {
  return ::testing::TempDir() + "fastrak_" + name + "_" + std::to_string(::getpid());
}

// Runs server.step(1) until stopped; counters may be read after join().
struct SimThread {
  DeviceServer& server;
  std::atomic<bool> stop{false};
  std::thread thread;
  explicit SimThread(DeviceServer& s)
      : server(s), thread([this] {
          while (!stop.load() && server.step(1)) {
          }
        }) {}
  ~SimThread() { join(); }
  void join() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
};

// A host on the PTY slave at a chosen speed (8N1 raw, no flow control).
class RawClient {
 public:
  RawClient(const std::string& path, speed_t speed) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ >= 0) set_speed(speed);
  }
  ~RawClient() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  bool ok() const { return fd_ >= 0; }
  void set_speed(speed_t speed) {
    termios tio{};
    ::tcgetattr(fd_, &tio);
    ::cfmakeraw(&tio);
    ::cfsetspeed(&tio, speed);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    ::tcsetattr(fd_, TCSANOW, &tio);
  }
  void send(const std::string& s) const { (void)!::write(fd_, s.data(), s.size()); }
  // Reads until `done(bytes)` holds or `timeout_ms` passes; returns what came.
  template <typename Done>
  std::string read_until(Done done, int timeout_ms) const {
    std::string got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!done(got)) {
      const int left = ::twister::test::ms_until(end);
      if (left == 0) break;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, left) <= 0) continue;
      char buf[512];
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n > 0) got.append(buf, static_cast<std::size_t>(n));
    }
    return got;
  }
  // Everything that arrives within `ms` (a deliberate quiet period: waits on poll).
  std::string read_for(int ms) const {
    return read_until([](const std::string&) { return false; }, ms);
  }
  // Bytes up to and including the first CR LF after `prefix` (empty on timeout).
  std::string read_line_starting(const std::string& prefix, int timeout_ms) const {
    const std::string got = read_until(
        [&](const std::string& s) {
          const auto at = s.find(prefix);
          return at != std::string::npos && s.find("\r\n", at) != std::string::npos;
        },
        timeout_ms);
    const auto at = got.find(prefix);
    if (at == std::string::npos) return {};
    const auto end = got.find("\r\n", at);
    return end == std::string::npos ? std::string{} : got.substr(at, end + 2 - at);
  }

 private:
  int fd_ = -1;
};

}  // namespace twister::sim::test_rig
