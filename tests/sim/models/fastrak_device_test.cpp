// The Fastrak device model driven by the real FastrakSession in virtual time, through
// SimFastrakStream (the PTY path is covered by the termios and acceptance tests):
// rates per active station, bandwidth drops, command replies, stylus e-mode, and each
// fault kind with the session recovering by itself.
#include "twister/sim/fastrak_device.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>

#include "fakes/fake_clock.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;
using tracker::OutputList;

tracker::FastrakSessionConfig session_config(Format format, int stations) {
  tracker::FastrakSessionConfig c;
  c.protocol.format = format;
  for (int s = 0; s < stations; ++s) {
    c.protocol.stations[static_cast<std::size_t>(s)].enabled = true;
    c.protocol.stations[static_cast<std::size_t>(s)].list =
        OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf});
  }
  c.ladder_char_pause_us = 20'000;
  c.reset_wait_us = 600'000;
  c.settle_us = 50'000;
  c.reply_timeout_us = 300'000;
  c.command_pause_us = 50'000;  // the simulator's default command times (40 ms)
  return c;
}

Scenario scenario(const std::string& text) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(parse_scenario(text, sc, err)) << err;
  return sc;
}

// The model behind SimFastrakStream (the station's in-process simulator port).
struct SimRig {
  ::twister::test::FakeClock clock{0};
  SimFastrakStream stream;
  const FastrakDevice& device;
  tracker::FastrakSession session;
  std::vector<std::pair<double, tracker::FastrakPose>> poses;

  SimRig(const Scenario& sc, const tracker::FastrakSessionConfig& cfg, FastrakDeviceConfig dev = {})
      : stream(clock, dev, sc), device(stream.device()), session(stream, clock, cfg) {}

  void run(double seconds, std::int64_t step_us = 1'000) {
    const auto end = clock.now_us() + static_cast<std::int64_t>(seconds * 1e6);
    while (clock.now_us() < end) {
      for (auto p = session.poll(); p.ok(); p = session.poll()) {
        poses.emplace_back(device.scenario_time_s(clock.now_us()), *p);
      }
      clock.advance_us(step_us);
    }
  }
  std::size_t count(int station, double from_s, double to_s) const {
    std::size_t n = 0;
    for (const auto& [t, p] : poses) n += p.station == station && t >= from_s && t < to_s;
    return n;
  }
};

TEST(FastrakDevice, TwoStationsShare120Hz) {
  SimRig rig(scenario("receivers 2\ncircle 1 12 0 3 4 2\n"), session_config(Format::binary, 2));
  rig.run(4.0);
  ASSERT_TRUE(rig.session.streaming());
  // Steady state: 60 Hz per station (allow one record of jitter at the edges).
  EXPECT_NEAR(static_cast<double>(rig.count(1, 2.0, 4.0)), 120.0, 2.0);
  EXPECT_NEAR(static_cast<double>(rig.count(2, 2.0, 4.0)), 120.0, 2.0);
  EXPECT_EQ(rig.device.counters().dropped_solutions, 0u);
}

TEST(FastrakDevice, PosesFollowTheScenarioTrajectory) {
  SimRig rig(scenario("receivers 1\nkey 0 1 10 0 0 0 0 0\nkey 10 1 20 10 -5 90 30 -45\n"),
             session_config(Format::binary, 1));
  rig.run(3.0);
  ASSERT_GT(rig.poses.size(), 100u);
  for (const auto& [t, p] : rig.poses) {
    // The record was sampled at most a cycle plus transmit time before `t`.
    EXPECT_NEAR(p.position[0], 10.0 + t, 0.05);
    EXPECT_NEAR(p.position[1], t, 0.05);
  }
}

TEST(FastrakDevice, AsciiAtLowBaudDropsWholeSolutions) {
  FastrakDeviceConfig dev;
  dev.baud = 9600;
  tracker::FastrakSessionConfig cfg = session_config(Format::ascii, 1);
  cfg.protocol.stations[0].list = OutputList::of({Item::position, Item::euler, Item::crlf});
  SimRig rig(scenario("receivers 1\n"), cfg, dev);
  rig.run(5.0);
  ASSERT_TRUE(rig.session.streaming());
  // 47 bytes at 960 bytes/s: about 20 records per second reach the host
  // (docs/fastrak-protocol.md §1).
  const double rate = static_cast<double>(rig.count(1, 3.0, 5.0)) / 2.0;
  EXPECT_GT(rate, 15.0);
  EXPECT_LT(rate, 25.0);
  EXPECT_GT(rig.device.counters().dropped_solutions, 100u);
}

TEST(FastrakDevice, StylusDefaultModeTogglesStreamAndSessionSendsE10) {
  // With e1,0 (the session sends it) a press does not stop the stream.
  SimRig rig(scenario("receivers 1\nkey 0 1 10 0 0 0 0 0 0\nkey 2.5 1 10 0 0 0 0 0 1\n"
                      "key 3 1 10 0 0 0 0 0 0\n"),
             session_config(Format::binary, 1));
  rig.run(4.0);
  EXPECT_GT(rig.count(1, 3.0, 4.0), 100u);
  bool pressed = false;
  for (const auto& [t, p] : rig.poses) pressed = pressed || p.button;
  EXPECT_TRUE(pressed);
}

TEST(FastrakDevice, RepliesToReadBacksAndUnknownCommands) {
  ::twister::test::FakeClock clock{0};
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  dev.command_time_us = instant_commands();  // all at once: processing time is not the point
  FastrakDevice device(dev, scenario("receivers 2\n"), 0);
  const std::string cmds = "O1\rl1\rZO1,2,99\rS";
  device.receive(reinterpret_cast<const std::byte*>(cmds.data()), cmds.size(), 10);
  std::vector<std::byte> out;
  device.advance(1'000'000, out);
  tracker::FastrakConfig pc;
  pc.stations[0].enabled = true;
  tracker::FastrakParser parser(pc);
  std::vector<tracker::FastrakEvent> ev;
  parser.feed(out, [&](const tracker::FastrakEvent& e) { ev.push_back(e); });
  ASSERT_EQ(ev.size(), 5u);
  EXPECT_EQ(ev[0].reply.command, 'O');
  EXPECT_EQ(ev[0].reply.length, 11);  // "21O 2 4 1" CR LF
  EXPECT_EQ(ev[1].reply.command, 'l');
  EXPECT_TRUE(ev[2].reply.is_error);
  EXPECT_EQ(ev[2].reply.error_code, -99);
  EXPECT_EQ(ev[3].reply.error_code, -3);  // item 99 out of range
  EXPECT_EQ(ev[4].kind, tracker::EventKind::status);
  EXPECT_EQ(ev[4].status.flags, 0x3F0);
}

// Each fault kind in virtual time: the session recovers by itself, every pose it
// emits is on the scenario's trajectory, and the counters show what happened.
struct FaultCase {
  const char* name;
  const char* faults;
  Format format;
};

// Names the case in test output instead of dumping its bytes.
void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.name; }

class FastrakDeviceFaults : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FastrakDeviceFaults, SessionRecoversAndEmitsOnlyTruePoses) {
  const FaultCase& fc = GetParam();
  const std::string text = std::string("receivers 2\nseed 7\n") +
                           "key 0 1 10 0 0 0 0 0\nkey 20 1 30 -10 5 40 20 10\n" +
                           "key 0 2 15 5 0 0 0 0\nkey 20 2 15 5 10 -60 0 0\n" + fc.faults;
  SimRig rig(scenario(text), session_config(fc.format, 2));
  rig.run(14.0);
  ASSERT_TRUE(rig.session.streaming()) << tracker::session_state_name(rig.session.state());
  // Recovered: both stations stream again in the last two seconds.
  EXPECT_GT(rig.count(1, 12.0, 14.0), 100u);
  EXPECT_GT(rig.count(2, 12.0, 14.0), 100u);
  for (const auto& [t, p] : rig.poses) {
    const double u = t / 20.0;
    const double x = p.station == 1 ? 10.0 + 20.0 * u : 15.0;
    ASSERT_NEAR(p.position[0], x, 0.1) << "station " << int(p.station) << " t=" << t;
    auto r = tracker::tracker_rotation(p, fc.format);
    ASSERT_TRUE(r.ok());
  }
  const auto& c = rig.session.counters();
  const auto& pc = rig.session.parser_counters();
  std::printf(
      "[%s] inits=%llu streams=%llu status_timeouts=%llu io=%llu silence=%llu "
      "garbage=%llu rejected=%llu resyncs=%llu dropped=%llu\n",
      fc.name, (unsigned long long)c.inits, (unsigned long long)c.streams_started,
      (unsigned long long)c.status_timeouts, (unsigned long long)c.io_errors,
      (unsigned long long)c.silence_faults, (unsigned long long)c.garbage_faults,
      (unsigned long long)c.rejected_poses, (unsigned long long)pc.resyncs,
      (unsigned long long)pc.dropped_bytes);
  const std::string name = fc.name;
  if (name == "noise" || name == "drop" || name == "truncate") {
    EXPECT_GE(pc.resyncs, 1u);
    EXPECT_EQ(c.streams_started, 1u);  // absorbed by the parser, no re-init needed
  } else if (name == "stall") {
    EXPECT_EQ(c.silence_faults, 1u);
    EXPECT_GE(c.streams_started, 2u);
  } else if (name == "hangup") {
    EXPECT_GE(c.io_errors, 1u);
    EXPECT_GE(c.streams_started, 2u);
  } else if (name == "wrongbaud") {
    EXPECT_GE(c.garbage_faults, 1u);
    EXPECT_GE(c.streams_started, 2u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllKinds, FastrakDeviceFaults,
    ::testing::Values(FaultCase{"noise", "fault 4 noise 300\nfault 5 noise 50\n", Format::binary},
                      FaultCase{"drop", "fault 4 drop 7\nfault 5 drop 100\n", Format::binary},
                      FaultCase{"truncate", "fault 4 truncate 5\n", Format::ascii},
                      FaultCase{"stall", "fault 4 stall 3\n", Format::binary},
                      FaultCase{"hangup", "fault 4 hangup 1.5\n", Format::binary},
                      FaultCase{"wrongbaud", "fault 4 wrongbaud 3\n", Format::ascii}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace twister::sim
