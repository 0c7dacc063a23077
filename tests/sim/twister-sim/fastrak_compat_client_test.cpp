// Compatibility of twister-sim with a driver that is not ours (issue 15): a small,
// independent Fastrak client written here from the manual's command descriptions, in
// the way common drivers (VRPN, Vrui) configure a unit. It shares nothing with the
// project's parser or session: POSIX termios, its own record decoding. On a PTY it
// checks the status record, output-list read-back, the filter commands and their
// read-back, binary continuous streaming (rate, record layout, values), and that a
// command sent without the drivers' pause waits in the unit's input buffer (issue 22).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "sim_pty_rig.hpp"

namespace twister::sim {
namespace {

// --- the independent client -------------------------------------------------------

class Client {
 public:
  explicit Client(const std::string& path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    termios t{};
    ::tcgetattr(fd_, &t);
    ::cfmakeraw(&t);  // 8N1 raw, no flow control (Vrui, VRPN)
    ::cfsetspeed(&t, B115200);
    t.c_cflag |= CLOCAL | CREAD;
    ::tcsetattr(fd_, TCSANOW, &t);
  }
  ~Client() { ::close(fd_); }
  bool ok() const { return fd_ >= 0; }
  // One command, then the pause a driver leaves after it (waiting on the port).
  void command(const std::string& text, int pause_ms) {
    (void)!::write(fd_, text.data(), text.size());
    if (pause_ms > 0) received_ += read_for(pause_ms);
  }
  void flush() {
    ::tcflush(fd_, TCIFLUSH);
    received_.clear();
  }
  std::string read_for(int ms) {
    std::string got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            end - std::chrono::steady_clock::now())
                            .count();
      if (left <= 0) return got;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left)) <= 0) continue;
      char buf[1024];
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n > 0) got.append(buf, static_cast<std::size_t>(n));
    }
  }
  // A '2'-led reply line of the given kind ("S", "O", "x"), reading up to `ms`.
  std::string reply(char kind, int ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    for (;;) {
      for (std::size_t i = 0; i + 2 < received_.size(); ++i) {
        if (received_[i] != '2' || received_[i + 2] != kind) continue;
        const auto lf = received_.find('\n', i);
        if (lf == std::string::npos) break;
        std::string line = received_.substr(i, lf + 1 - i);
        received_.erase(0, lf + 1);
        return line;
      }
      if (std::chrono::steady_clock::now() >= end) return {};
      received_ += read_for(20);
    }
  }

 private:
  int fd_ = -1;
  std::string received_;
};

float le_float(const char* p) {
  std::uint32_t u = 0;
  for (int i = 3; i >= 0; --i) u = (u << 8) | static_cast<unsigned char>(p[i]);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// VRPN's binary record for O s,2,11,16,0: '0', station, status, x y z, q0..q3,
// stylus (' ' and '0'/'1'), ' ' = 34 bytes.
struct Record {
  int station;
  char status;
  float pos[3];
  float q[4];
  char stylus;
};
constexpr std::size_t kRecordBytes = 34;

// Scans for records the way VRPN does (header, then the full length, then the
// trailing space); returns how many; counts per station in `per_station`.
int decode(const std::string& s, Record* last, int per_station[2]) {
  int n = 0;
  for (std::size_t i = 0; i + kRecordBytes <= s.size();) {
    const char st = s[i + 1];
    const char status = s[i + 2];
    const bool header = s[i] == '0' && (st == '1' || st == '2') &&
                        (status == ' ' || std::isalpha(static_cast<unsigned char>(status)));
    if (!header || s[i + kRecordBytes - 1] != ' ' || s[i + 31] != ' ') {
      ++i;
      continue;
    }
    Record& r = last[st - '1'];
    r.station = st - '0';
    r.status = status;
    for (int k = 0; k < 3; ++k) r.pos[k] = le_float(s.data() + i + 3 + 4 * k);
    for (int k = 0; k < 4; ++k) r.q[k] = le_float(s.data() + i + 15 + 4 * k);
    r.stylus = s[i + 32];
    ++per_station[st - '1'];
    ++n;
    i += kRecordBytes;
  }
  return n;
}

// --- the check ----------------------------------------------------------------------

TEST(FastrakCompatClient, ConfiguresLikeCommonDriversAndStreams) {
  const std::string link = test_rig::link_path("compat");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  FastrakDevice device(dev,
                       test_rig::scenario("receivers 2\nkey 0 1 10 -4 2 90 0 0\n"
                                          "key 0 2 12 4 -3 0 0 0\n"),
                       0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::usb_adapter});
  ASSERT_TRUE(server.start());
  test_rig::SimThread sim(server);
  Client c(link);
  ASSERT_TRUE(c.ok());

  // Reset rung 1 (VRPN): leave continuous mode, flush, ask for status.
  c.command("c", 100);
  c.flush();
  c.command("S", 0);
  const std::string status = c.reply('S', 1000);
  ASSERT_EQ(status.size(), 55u) << status;  // VRPN: byte 1 '2', byte 55 LF
  // Byte 2 is the station the unit was busy with (manual: it varies); flags 3F0 =
  // ASCII, inches, polled (manual's table).
  EXPECT_EQ(status.substr(2, 4), "S3F0");
  EXPECT_EQ(status.substr(53), "\r\n");

  // Output lists with VRPN's pause, read back (one 2-character field per item).
  for (const char* st : {"1", "2"}) {
    c.command(std::string("l") + st + ",1\r", 100);
    c.command(std::string("O") + st + ",2,11,16,0\r", 50);
  }
  c.command("O1\r", 0);
  EXPECT_EQ(c.reply('O', 1000), "21O 21116 0\r\n");

  // Filters as VRPN sends them, with its 1 s pause; then the read-back record.
  c.command("x0.2,0.2,0.8,0.8\r", 1000);
  c.command("v0.2,0.2,0.8,0.8\r", 1000);
  c.command("x\r", 0);
  const std::string x = c.reply('x', 2000);
  ASSERT_EQ(x.size(), 33u) << x;
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(std::stod(x.substr(3 + 7 * k, 7)), k < 2 ? 0.2 : 0.8, 1e-9) << x;
  }

  // Stylus mode, binary, status check, continuous.
  c.command("e1,0\r", 100);
  c.command("f", 50);
  c.command("S", 0);
  EXPECT_EQ(c.reply('S', 1000).substr(2, 4), "S3F1");  // binary now
  c.flush();
  const auto start = std::chrono::steady_clock::now();
  c.command("C", 0);
  std::string stream;
  while (stream.size() < kRecordBytes) stream += c.read_for(20);
  const auto first_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                            std::chrono::steady_clock::now() - start)
                            .count();
  stream += c.read_for(2000);
  Record last[2]{};
  int per_station[2] = {0, 0};
  const int records = decode(stream, last, per_station);

  // A driver that does not wait (VRPN writes its reset commands back to back): the
  // read-back waited in the unit's input buffer while `O` was processed, and comes
  // (issue 22; before, the unit lost it).
  c.command("c", 100);
  c.flush();
  c.command("O1,2,4,1\rO1\r", 300);
  const std::string buffered = c.reply('O', 10);
  sim.join();
  ::unlink(link.c_str());

  std::printf(
      "[compat] first record %lld ms after C; %d records in ~2 s (station 1 %d, "
      "station 2 %d); %zu bytes\n",
      static_cast<long long>(first_ms), records, per_station[0], per_station[1], stream.size());
  EXPECT_LT(first_ms, 200);
  EXPECT_EQ(static_cast<std::size_t>(records) * kRecordBytes, stream.size());  // nothing else
  EXPECT_GE(per_station[0], 110);  // 60 Hz each for ~2 s
  EXPECT_LE(per_station[0], 135);
  EXPECT_NEAR(per_station[0], per_station[1], 1);
  EXPECT_NEAR(last[0].pos[0], 10.0f, 1e-5);
  EXPECT_NEAR(last[0].pos[1], -4.0f, 1e-5);
  EXPECT_NEAR(last[1].pos[2], -3.0f, 1e-5);
  EXPECT_NEAR(last[0].q[0], std::sqrt(0.5f), 1e-5);  // azimuth 90: about z
  EXPECT_NEAR(last[0].q[3], std::sqrt(0.5f), 1e-5);
  EXPECT_EQ(last[0].stylus, '0');
  EXPECT_EQ(last[0].status, ' ');
  EXPECT_EQ(buffered, "21O 2 4 1\r\n");
}

}  // namespace
}  // namespace twister::sim
