// twister-sim's server on a real PTY with the station's FastrakSession on the real
// termios backend (issue 15): in-record corruption caught by plausibility, not
// framing (point 4), status letters accepted as warnings (point 6), a drop budget that
// no longer outlives the stream (point 7), a hang-up behind a fixed port (point 8) and
// the 16-bit packed format end to end (point 9). Real time, a few seconds per case;
// the loop waits on the port's descriptor.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "sim_pty_rig.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/hal/termios_byte_stream.hpp"
#include "twister/tracker/fastrak_session.hpp"

namespace twister::sim {
namespace {

using test_rig::SimThread;
using tracker::Format;
using tracker::Item;
using tracker::OutputList;

tracker::FastrakSessionConfig session_config(Format format, OutputList list) {
  tracker::FastrakSessionConfig cfg;
  cfg.protocol.format = format;
  for (std::size_t s = 0; s < 2; ++s) cfg.protocol.stations[s] = {true, list};
  cfg.ladder_char_pause_us = 20'000;
  cfg.reset_wait_us = 600'000;  // the simulator's ^Y takes 500 ms by default
  cfg.settle_us = 50'000;
  cfg.reply_timeout_us = 300'000;
  cfg.command_pause_us = 50'000;
  cfg.silence_timeout_us = 1'000'000;
  cfg.backoff.initial_us = 100'000;
  return cfg;
}

const OutputList kBinaryList = OutputList::of({Item::position, Item::quaternion, Item::crlf});

// The session on the PTY link; `on_pose` sees every pose; runs until `done()` or
// `seconds` pass.
struct Host {
  hal::TermiosByteStream port;
  hal::MonotonicClock clock;
  tracker::FastrakSession session;
  Host(const std::string& link, const tracker::FastrakSessionConfig& cfg)
      : port({link, 115200, hal::FlowControl::none}), session(port, clock, cfg) {}
  void run(double seconds, const std::function<void(const tracker::FastrakPose&)>& on_pose,
           const std::function<bool()>& done) {
    const auto end = std::chrono::steady_clock::now() +
                     std::chrono::milliseconds(static_cast<int>(seconds * 1000));
    while (std::chrono::steady_clock::now() < end && !done()) {
      for (auto p = session.poll(); p.ok(); p = session.poll()) on_pose(*p);
      if (!::twister::test::wait_ready(port, 5) && !port.is_open()) ::poll(nullptr, 0, 5);
    }
  }
};

// Point 4: a resting hand, every record corrupted for 2.5 s: the parser's checks and
// the continuity check reject what they can; framing sees nothing; every pose that
// reaches the consumer is within the continuity limits of the truth.
TEST(FastrakFaultPty, InRecordCorruptionIsCaughtByPlausibilityNotFraming) {
  const std::string link = test_rig::link_path("corrupt");
  FastrakDevice device({},
                       test_rig::scenario("receivers 2\nseed 3\nkey 0 1 10 -4 2 30 10 5\n"
                                          "key 0 2 12 4 -3 -40 10 20\n"
                                          "fault 2 corrupt 300\n"),
                       0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::usb_adapter});
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  const auto cfg = session_config(Format::binary, kBinaryList);
  Host host(link, cfg);
  const glm::dvec3 truth[2] = {{10, -4, 2}, {12, 4, -3}};
  double worst = 0.0;
  std::size_t poses = 0, off_truth = 0;
  std::chrono::steady_clock::time_point last[2] = {std::chrono::steady_clock::now(),
                                                   std::chrono::steady_clock::now()};
  double worst_excess = -1e9;
  host.run(
      8.0,
      [&](const tracker::FastrakPose& p) {
        ++poses;
        const auto now = std::chrono::steady_clock::now();
        const int i = p.station - 1;
        const double dt = std::max(std::chrono::duration<double>(now - last[i]).count(), 8.333e-3);
        last[i] = now;
        const double off =
            glm::length(glm::dvec3(p.position[0], p.position[1], p.position[2]) - truth[i]);
        worst = std::max(worst, off);
        off_truth += off > 1e-3;
        worst_excess = std::max(worst_excess, off - (cfg.continuity.max_speed_in_s * dt +
                                                     cfg.continuity.position_slack_in));
      },
      [&] { return poses > 450; });  // past the 2.5 s of corrupted records
  sim.join();
  const auto& c = host.session.counters();
  const auto& pc = host.session.parser_counters();
  std::printf(
      "[pty corrupt] corrupted=%llu poses=%zu parser_rejects=%llu jump_rejects=%llu "
      "resyncs=%llu passed_but_wrong=%zu (worst %.3f in) streams=%llu\n",
      static_cast<unsigned long long>(device.counters().corrupted_records), poses,
      static_cast<unsigned long long>(c.rejected_poses),
      static_cast<unsigned long long>(c.jump_rejects), static_cast<unsigned long long>(pc.resyncs),
      off_truth, worst, static_cast<unsigned long long>(c.streams_started));
  ::unlink(link.c_str());
  EXPECT_EQ(device.counters().corrupted_records, 300u);
  EXPECT_GT(c.rejected_poses, 0u);
  EXPECT_GT(c.jump_rejects, 0u);
  EXPECT_EQ(pc.resyncs, 0u);
  EXPECT_EQ(c.streams_started, 1u);
  EXPECT_LE(worst_excess, 0.0);
}

// Point 6: status letters are warnings; the poses are used and the code is kept.
TEST(FastrakFaultPty, StatusLettersAreAcceptedAndCounted) {
  const std::string link = test_rig::link_path("status");
  FastrakDevice device({}, test_rig::scenario("receivers 2\nstatus 2 1 E 1\nstatus 2 2 y 1\n"), 0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::usb_adapter});
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  Host host(link, session_config(Format::ascii,
                                 OutputList::of({Item::position, Item::euler, Item::crlf})));
  std::size_t letters[2] = {0, 0};
  std::size_t clean_after = 0;  // poses without a letter after both stations had theirs
  host.run(
      6.0,
      [&](const tracker::FastrakPose& p) {
        letters[p.station - 1] += p.status != ' ';
        clean_after += letters[0] > 40 && letters[1] > 40 && p.status == ' ';
      },
      [&] { return clean_after > 20; });
  sim.join();
  ::unlink(link.c_str());
  const auto& c = host.session.counters();
  std::printf(
      "[pty status] warning poses=%llu (station 1 'E' %zu, station 2 'y' %zu), "
      "rejected=%llu\n",
      static_cast<unsigned long long>(c.warning_poses), letters[0], letters[1],
      static_cast<unsigned long long>(c.rejected_poses));
  EXPECT_GT(letters[0], 40u);
  EXPECT_GT(letters[1], 40u);
  EXPECT_EQ(c.rejected_poses, 0u);
  EXPECT_EQ(host.session.parser_counters().resyncs, 0u);
}

// Point 7: a drop budget far larger than the stream: the session sees silence, stops
// the stream with `c`, the budget expires, and start-up #2 succeeds.
TEST(FastrakFaultPty, DropBudgetDoesNotOutliveTheStream) {
  const std::string link = test_rig::link_path("drop");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 200'000;
  FastrakDevice device(dev, test_rig::scenario("receivers 2\nfault 2 drop 100000000\n"), 0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::usb_adapter});
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  Host host(link, session_config(Format::binary, kBinaryList));
  std::size_t poses_after = 0;
  host.run(
      10.0,
      [&](const tracker::FastrakPose&) {
        poses_after += host.session.counters().streams_started >= 2;
      },
      [&] { return poses_after > 100; });
  sim.join();
  ::unlink(link.c_str());
  const auto& c = host.session.counters();
  std::printf("[pty drop] streams=%llu silence=%llu bytes eaten=%llu budget expired=%llu\n",
              static_cast<unsigned long long>(c.streams_started),
              static_cast<unsigned long long>(c.silence_faults),
              static_cast<unsigned long long>(device.counters().dropped_bytes),
              static_cast<unsigned long long>(device.counters().drop_expired));
  EXPECT_GE(c.streams_started, 2u);
  EXPECT_GT(poses_after, 100u);
  EXPECT_GT(device.counters().drop_expired, 0u);
}

// Point 8: behind a fixed port a hang-up keeps the tty and its link; the host sees
// silence (not an I/O error) and recovers when the unit is back.
TEST(FastrakFaultPty, HangUpBehindAFixedPortKeepsTheLink) {
  const std::string link = test_rig::link_path("fixed");
  FastrakDeviceConfig dev;
  dev.reset_time_us = 200'000;
  FastrakDevice device(dev, test_rig::scenario("receivers 2\nfault 2 hangup 1.5\n"), 0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::fixed});
  ASSERT_TRUE(server.start());
  const std::string slave = server.slave_path();
  SimThread sim(server);
  Host host(link, session_config(Format::binary, kBinaryList));
  bool link_always_there = true;
  std::size_t poses_after = 0;
  host.run(
      10.0,
      [&](const tracker::FastrakPose&) {
        poses_after += host.session.counters().streams_started >= 2;
      },
      [&] {
        char target[256] = {};
        const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
        link_always_there = link_always_there && n > 0 && slave == target;
        return poses_after > 100;
      });
  sim.join();
  ::unlink(link.c_str());
  const auto& c = host.session.counters();
  std::printf("[pty fixed] hangups=%llu ptys=%llu io_errors=%llu silence=%llu streams=%llu\n",
              static_cast<unsigned long long>(server.counters().hangups),
              static_cast<unsigned long long>(server.counters().ptys_opened),
              static_cast<unsigned long long>(c.io_errors),
              static_cast<unsigned long long>(c.silence_faults),
              static_cast<unsigned long long>(c.streams_started));
  EXPECT_TRUE(link_always_there);
  EXPECT_EQ(server.counters().hangups, 0u);
  EXPECT_EQ(server.counters().ptys_opened, 1u);
  EXPECT_EQ(c.io_errors, 0u);
  EXPECT_GE(c.silence_faults, 1u);
  EXPECT_GE(c.streams_started, 2u);
}

// Point 9: an Isotrak-style unit whose `f` is the 16-bit packed format, configured by
// the session with VRPN's Isotrak list (2,11: 20-byte records, no terminator).
TEST(FastrakFaultPty, Packed16EndToEnd) {
  const std::string link = test_rig::link_path("packed16");
  FastrakDeviceConfig dev;
  dev.packed16 = true;
  FastrakDevice device(dev,
                       test_rig::scenario("receivers 2\nkey 0 1 10 0 0 0 0 0\n"
                                          "key 60 1 70 -30 6 60 30 0\n"),
                       0);
  DeviceServer server(device, ServeOptions{link, {}, 115200, PortKind::usb_adapter});
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  Host host(link,
            session_config(Format::binary16, OutputList::of({Item::position, Item::quaternion})));
  std::size_t poses = 0;
  double worst = 0.0;
  host.run(
      5.0,
      [&](const tracker::FastrakPose& p) {
        ++poses;
        if (p.station == 1) {  // on the path x = 10 + s, y = -s / 2, z = s / 10
          const double s = p.position[0] - 10.0;
          worst = std::max(
              {worst, std::fabs(p.position[1] + s / 2.0), std::fabs(p.position[2] - s / 10.0)});
        }
      },
      [&] { return poses > 200; });
  sim.join();
  ::unlink(link.c_str());
  std::printf(
      "[pty packed16] poses=%zu worst off-path %.4f in (one count = %.4f in), "
      "rejected=%llu resyncs=%llu\n",
      poses, worst, 65.48 / 32768,
      static_cast<unsigned long long>(host.session.counters().rejected_poses),
      static_cast<unsigned long long>(host.session.parser_counters().resyncs));
  EXPECT_GT(poses, 200u);
  EXPECT_LT(worst, 2 * 65.48 / 32768 + 1e-4);
  EXPECT_EQ(host.session.counters().rejected_poses, 0u);
}

}  // namespace
}  // namespace twister::sim
