// twister-sim's server on a real PTY, with a raw host on the slave (issue 15): the
// adaptive filter and its replies (point 1), a host at the wrong baud (points 2 and
// 5) and command processing times (point 3). Real time; each case a few seconds;
// waits are poll(2) on the client's descriptor, assertions are on bytes and order.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <vector>

#include "sim_pty_rig.hpp"
#include "twister/tracker/fastrak_parser.hpp"

namespace twister::sim {
namespace {

using test_rig::RawClient;
using test_rig::SimThread;
using tracker::EventKind;
using tracker::Format;
using tracker::Item;
using tracker::OutputList;

std::vector<tracker::FastrakEvent> parse(const std::string& bytes,
                                         const tracker::FastrakConfig& config) {
  tracker::FastrakParser parser(config);
  std::vector<tracker::FastrakEvent> out;
  parser.feed(std::as_bytes(std::span<const char>(bytes.data(), bytes.size())),
              [&](const tracker::FastrakEvent& e) { out.push_back(e); });
  for (auto e = parser.finish(); e.ok(); e = parser.finish()) out.push_back(*e);
  return out;
}

tracker::FastrakConfig stations(Format f, int n, OutputList list) {
  tracker::FastrakConfig c;
  c.format = f;
  for (int s = 0; s < n; ++s) c.stations[static_cast<std::size_t>(s)] = {true, list};
  return c;
}

// Point 1: x1 gets an error reply, x<> the 33-byte record, and a filter set with x
// shapes a 10-inch step the way the manual's exponential filter does.
TEST(FastrakFidelityPty, FilterRepliesAndStepResponse) {
  const Scenario sc = test_rig::scenario(
      "receivers 1\nkey 0 1 10 -4 2 0 0 0\nkey 4 1 10 -4 2 0 0 0\nkey 4.0001 1 20 -4 2 0 0 0\n");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  FastrakDevice device(dev, sc, 0);
  ServeOptions opts;
  opts.link = test_rig::link_path("filter");
  DeviceServer server(device, opts);
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  RawClient host(opts.link, B115200);
  ASSERT_TRUE(host.ok());

  host.send("x1\r");
  const std::string error = host.read_line_starting("2 E", 2000);
  EXPECT_EQ(error.substr(0, 28), "2 E*ERROR* x1 *ERROR* EC -3 ") << error;
  host.send("x\r");
  EXPECT_EQ(host.read_line_starting("2 x", 2000), "2 x  0.200  1.000  0.800  0.950\r\n");
  // The filter is set; the unit is deaf while it processes x (a read-back proves it
  // is done), then the list, binary, continuous.
  host.send("x0.5,0.25,0.26,0.9\r");
  host.read_for(600);
  host.send("x\r");
  EXPECT_EQ(host.read_line_starting("2 x", 2000), "2 x  0.500  0.250  0.260  0.900\r\n");
  host.send("O1,2,11,1\r");
  host.read_for(100);
  host.send("fC");
  const std::string bytes =
      host.read_until([](const std::string& s) { return s.size() >= 33u * 120u * 7u / 2u; }, 9000);
  sim.join();
  std::vector<double> x;
  for (const auto& e :
       parse(bytes, stations(Format::binary, 1,
                             OutputList::of({Item::position, Item::quaternion, Item::crlf})))) {
    if (e.kind == EventKind::pose) x.push_back(e.pose.position[0]);
  }
  ASSERT_GT(x.size(), 300u);  // 3.5 s of records; the step comes about 2 s in
  std::size_t step = 0;       // first record after the step
  while (step < x.size() && x[step] < 10.001) ++step;
  ASSERT_GT(step, 10u);
  ASSERT_LT(step + 20, x.size());
  for (std::size_t k = 0; k < step; ++k) EXPECT_NEAR(x[k], 10.0, 1e-5);  // still hand
  EXPECT_LE(x[step], 10.0 + 10.0 * 0.2601);  // the first output moves a <= FHIGH of the way
  std::printf("[pty filter] 10 in step, a in [0.25, 0.26]: records after the step:");
  for (std::size_t k = step; k < step + 8; ++k) std::printf(" %.3f", x[k]);
  std::printf("\n");
  // Each following record closes (1 - a) of the remaining gap (manual, eq. E-1).
  for (std::size_t k = step + 1; k < step + 15; ++k) {
    const double ratio = (20.0 - x[k]) / (20.0 - x[k - 1]);
    EXPECT_GE(ratio, 0.74 - 1e-3) << k;
    EXPECT_LE(ratio, 0.75 + 1e-3) << k;
  }
}

// Points 2 and 5: at 19 200 baud against a unit at 115 200 the host sees mostly
// silence and a little junk, nothing parseable, and its commands are not understood;
// at the right speed the same link works.
TEST(FastrakFidelityPty, WrongBaudIsMostlySilenceAndNothingParses) {
  const Scenario sc = test_rig::scenario("receivers 2\n");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  dev.start_continuous = true;  // the unit streams: 2 x 47 bytes x 60 Hz = 5640 bytes/s
  FastrakDevice device(dev, sc, 0);
  ServeOptions opts;
  opts.link = test_rig::link_path("baud");
  DeviceServer server(device, opts);
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  RawClient host(opts.link, B19200);
  ASSERT_TRUE(host.ok());
  host.read_for(200);  // the server reads the new speed within a step
  host.send("S");
  const std::string junk = host.read_for(1500);
  const tracker::FastrakConfig ascii2 =
      stations(Format::ascii, 2, OutputList::of({Item::position, Item::euler, Item::crlf}));
  std::size_t parsed = 0;
  for (const auto& e : parse(junk, ascii2)) parsed += e.kind != EventKind::resync;
  host.set_speed(B115200);
  host.read_for(200);
  host.send("S");
  const std::string good = host.read_until(
      [](const std::string& s) { return s.find("21S") != std::string::npos || s.size() > 2000; },
      2000);
  const std::string more = host.read_for(1000);
  sim.join();
  std::size_t poses = 0, status = 0;
  for (const auto& e : parse(good + more, ascii2)) {
    poses += e.kind == EventKind::pose;
    status += e.kind == EventKind::status;
  }
  const auto& c = device.counters();
  std::printf(
      "[pty baud] 1.5 s at 19200 vs 115200: %zu junk bytes, %llu lost, %zu parsed; "
      "then at 115200: %zu poses in ~1 s, %zu status\n",
      junk.size(), static_cast<unsigned long long>(c.misclock_lost), parsed, poses, status);
  EXPECT_EQ(parsed, 0u);
  EXPECT_GT(junk.size(), 0u);                   // occasional junk ...
  EXPECT_LT(junk.size() * 8, 5640u * 3u / 2u);  // ... but mostly silence
  EXPECT_EQ(status, 1u);
  EXPECT_GT(poses, 60u);
  EXPECT_EQ(server.counters().host_baud, 115200);
}

// Point 3: commands sent while the unit still processes the previous one are lost;
// replies leave only when the command is done.
TEST(FastrakFidelityPty, CommandsSentTooEarlyAreLost) {
  const Scenario sc = test_rig::scenario("receivers 1\n");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  dev.input_buffer_bytes = 0;  // a unit without an input buffer (the default has one)
  FastrakDevice device(dev, sc, 0);
  ServeOptions opts;
  opts.link = test_rig::link_path("timing");
  DeviceServer server(device, opts);
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  RawClient host(opts.link, B115200);
  ASSERT_TRUE(host.ok());
  host.send("O1,2,11,1\rO1\r");  // no pause: the read-back is lost
  EXPECT_EQ(host.read_for(300), "");
  host.send("O1\r");  // 300 ms later: heard
  EXPECT_EQ(host.read_line_starting("21O", 2000), "21O 211 1\r\n");
  const auto sent = std::chrono::steady_clock::now();
  host.send("x\r");
  EXPECT_EQ(host.read_line_starting("2 x", 3000).size(), 33u);
  const auto waited = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - sent);
  sim.join();
  std::printf("[pty timing] x reply after %lld ms; bytes lost to early commands: %llu\n",
              static_cast<long long>(waited.count()),
              static_cast<unsigned long long>(device.counters().input_lost));
  EXPECT_GE(waited.count(), 500);  // the unit cannot answer before it is done
  EXPECT_EQ(device.counters().input_lost, 3u);
}

}  // namespace
}  // namespace twister::sim
