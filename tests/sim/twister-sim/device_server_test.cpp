// DeviceServer modes not covered by the acceptance test: HIL mode on a tty given by
// path (a PTY slave stands in for the rig's serial port; the test plays the host on
// the master side), and PTY mode's printed path and link.
#include "device_server.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "support/pty_pair.hpp"

namespace twister::sim {
namespace {

std::string pump(DeviceServer& server, int master, int ms) {
  std::string out;
  for (int i = 0; i < ms; ++i) {
    const hal::Expected<void> stepped = server.step(1);
    EXPECT_TRUE(stepped) << (stepped ? "" : stepped.error().message);
    char buf[512];
    const ssize_t n = ::read(master, buf, sizeof buf);
    if (n > 0) out.append(buf, static_cast<std::size_t>(n));
  }
  return out;
}

TEST(DeviceServer, HilModeServesARealTtyPath) {
  const ::twister::test::PtyPair pty;
  ASSERT_GE(pty.master, 0);
  ASSERT_FALSE(pty.slave.empty());  // grantpt, unlockpt and ptsname succeeded
  const int master = pty.master;
  Scenario sc;
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  FastrakDevice device(dev, sc, 0);
  ServeOptions opts;
  opts.device = pty.slave;
  DeviceServer server(device, opts);
  const hal::Expected<void> started = server.start();
  ASSERT_TRUE(started) << started.error().message;
  EXPECT_EQ(server.slave_path(), opts.device);
  ASSERT_EQ(::write(master, "S", 1), 1);
  const std::string status = pump(server, master, 100);
  ASSERT_EQ(status.size(), 55u);
  EXPECT_EQ(status.substr(0, 6), "21S3F0");
  ASSERT_EQ(::write(master, "P", 1), 1);
  const std::string records = pump(server, master, 100);
  // Default list 2,4,1 in ASCII for the two default receivers: 2 x 47 bytes.
  ASSERT_EQ(records.size(), 94u);
  EXPECT_EQ(records.substr(0, 3), "01 ");
  EXPECT_EQ(records.substr(47, 3), "02 ");
}

TEST(DeviceServer, PtyModeLinksTheSlave) {
  Scenario sc;
  FastrakDevice device({}, sc, 0);
  ServeOptions opts;
  opts.link = ::testing::TempDir() + "fastrak_server_" + std::to_string(::getpid());
  DeviceServer server(device, opts);
  const hal::Expected<void> started = server.start();
  ASSERT_TRUE(started) << started.error().message;
  char target[256] = {};
  const ssize_t n = ::readlink(opts.link.c_str(), target, sizeof target - 1);
  ASSERT_GT(n, 0);
  EXPECT_EQ(std::string(target), server.slave_path());
  EXPECT_EQ(server.counters().ptys_opened, 1u);
  ::unlink(opts.link.c_str());
}

}  // namespace
}  // namespace twister::sim
