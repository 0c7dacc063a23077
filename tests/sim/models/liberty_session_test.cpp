// Issue 22: the station's tracker session with model liberty / patriot, driven by the
// device model of `twister-sim --model liberty|patriot` through SimFastrakStream in
// virtual time. The session starts the unit in the Liberty's dialect (docs/liberty-protocol.md
// §9: WhoAmI, the lists in its item codes, F1, C), then reads its frames with
// LibertyParser: the poses equal the Fastrak run's as floats, and lost tracking, resync and the
// counters behave as for the Fastrak (label devices).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fakes/fake_clock.hpp"
#include "twister/sim/fastrak_device.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#include "twister/tracker/fastrak_session.hpp"

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;
using tracker::OutputList;
using tracker::TrackerModel;

constexpr const char* kMotion =
    "receivers 2\nseed 7\n"
    "key 0 1 10 0 0 0 0 0\nkey 3 1 13 -1.5 0.75 6 3 1.5 1\nkey 4 1 14 -2 1 8 4 2\n"
    "key 20 1 30 -10 5 40 20 10\n"
    "key 0 2 15 5 0 0 0 0\nkey 20 2 15 5 10 -60 0 0\n";

tracker::FastrakSessionConfig session_config(TrackerModel model) {
  tracker::FastrakSessionConfig c;
  c.model = model;
  c.protocol.format = Format::binary;
  c.protocol.stations[0] = {
      true, OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf})};
  c.protocol.stations[1] = {true, OutputList::of({Item::position, Item::quaternion, Item::crlf})};
  c.ladder_char_pause_us = 20'000;
  c.reset_wait_us = 600'000;
  c.settle_us = 50'000;
  c.reply_timeout_us = 300'000;
  c.command_pause_us = 50'000;
  return c;
}

Scenario scenario(const std::string& text) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(parse_scenario(text, sc, err)) << err;
  return sc;
}

DeviceModel device_model(TrackerModel m) {
  return m == TrackerModel::liberty   ? DeviceModel::liberty
         : m == TrackerModel::patriot ? DeviceModel::patriot
                                      : DeviceModel::fastrak;
}

struct Rig {
  ::twister::test::FakeClock clock{0};
  SimFastrakStream stream;
  tracker::FastrakSession session;
  std::vector<tracker::FastrakPose> poses;

  Rig(const std::string& text, TrackerModel session_model, TrackerModel device)
      : stream(clock, device_config(device), scenario(text)),
        session(stream, clock, session_config(session_model)) {}

  static FastrakDeviceConfig device_config(TrackerModel m) {
    FastrakDeviceConfig d;
    d.model = device_model(m);
    return d;
  }

  void run(double seconds) {
    const auto end = clock.now_us() + static_cast<std::int64_t>(seconds * 1e6);
    while (clock.now_us() < end) {
      for (auto p = session.poll(); p.ok(); p = session.poll()) poses.push_back(*p);
      clock.advance_us(1'000);
    }
  }
};

class LibertySession : public ::testing::TestWithParam<TrackerModel> {};

TEST_P(LibertySession, PosesEqualTheFastrakRunsAsFloats) {
  Rig rig(kMotion, GetParam(), GetParam());
  rig.run(6.0);
  // The model gives the 120 Hz cycles to the stations in turn from `C`: the Fastrak
  // run is made with its station 1 on the Liberty run's cycles (its start-up one cycle
  // later when needed).
  Rig fastrak(kMotion, TrackerModel::fastrak, TrackerModel::fastrak);
  fastrak.run(6.0);
  const auto in_phase = [&](const Rig& other) {
    for (const auto& p : rig.poses)
      if (p.station == other.poses[0].station && p.position == other.poses[0].position) return true;
    return false;
  };
  Rig late(kMotion, TrackerModel::fastrak, TrackerModel::fastrak);
  late.clock.advance_us(8'334);
  late.run(6.0);
  if (!in_phase(fastrak)) std::swap(fastrak.poses, late.poses);
  ASSERT_TRUE(rig.session.streaming()) << tracker::session_state_name(rig.session.state());
  EXPECT_GE(rig.poses.size(), 400u);
  // The Liberty's own start-up is shorter than the Fastrak's: it streams from an earlier
  // cycle. From the Fastrak run's first pose on, the same cycles: the same poses.
  std::size_t start = 0;
  while (start < rig.poses.size() && (rig.poses[start].station != fastrak.poses[0].station ||
                                      rig.poses[start].position != fastrak.poses[0].position)) {
    ++start;
  }
  ASSERT_LT(start, 240u) << "the Fastrak run's first pose is none of the Liberty's first 2 s";
  const std::size_t n = std::min(rig.poses.size() - start, fastrak.poses.size()) - 1;
  ASSERT_GE(n, 400u);
  bool pressed = false;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = rig.poses[start + i];
    const auto& b = fastrak.poses[i];
    ASSERT_EQ(a.station, b.station) << i;
    for (std::size_t k = 0; k < 3; ++k) ASSERT_FLOAT_EQ(a.position[k], b.position[k]) << i;
    for (std::size_t k = 0; k < 4; ++k) ASSERT_FLOAT_EQ(a.quaternion[k], b.quaternion[k]) << i;
    ASSERT_EQ(a.button, b.button) << i;
    pressed = pressed || a.button;
  }
  EXPECT_TRUE(pressed);  // the stylus item travels in the frames
  // The unit took the lists in its own item codes (O1,2,7,10,1 and O2,2,7,1): they read
  // back as the station's Fastrak lists.
  const auto want = session_config(GetParam()).protocol;
  for (std::size_t st = 0; st < 2; ++st) {
    const auto& got = rig.stream.device().protocol().stations[st].list;
    ASSERT_EQ(got.count, want.stations[st].list.count) << st;
    for (std::size_t i = 0; i < got.count; ++i)
      EXPECT_EQ(got.items[i], want.stations[st].list.items[i]);
  }
  EXPECT_EQ(rig.stream.device().counters().command_errors, 0u);
  const auto& c = rig.session.counters();
  EXPECT_EQ(c.streams_started, 1u);
  EXPECT_EQ(c.rejected_poses, 0u);
  EXPECT_EQ(rig.session.liberty_parser_counters().bad_frames, 0u);
  EXPECT_EQ(rig.session.liberty_parser_counters().poses, c.poses + c.jump_rejects);
}

TEST_P(LibertySession, NoiseIsResyncedWithoutReinitialising) {
  Rig rig(std::string(kMotion) + "fault 4 noise 300\nfault 5 noise 50\nfault 5.5 drop 20\n",
          GetParam(), GetParam());
  rig.run(8.0);
  ASSERT_TRUE(rig.session.streaming());
  EXPECT_GE(rig.session.liberty_parser_counters().resyncs, 2u);
  EXPECT_GT(rig.session.liberty_parser_counters().dropped_bytes, 0u);
  EXPECT_EQ(rig.session.counters().streams_started, 1u);
  EXPECT_GE(rig.poses.size(), 700u);
}

TEST_P(LibertySession, HangupAndStallAreLostTrackingAndRecover) {
  Rig rig(std::string(kMotion) + "fault 4 hangup 1.5\nfault 9 stall 3\n", GetParam(), GetParam());
  rig.run(16.0);
  ASSERT_TRUE(rig.session.streaming());
  const auto& c = rig.session.counters();
  EXPECT_GE(c.io_errors, 1u);
  EXPECT_EQ(c.silence_faults, 1u);
  EXPECT_GE(c.streams_started, 3u);
  // Streaming again at the end: the last second brought poses of both stations.
  std::size_t tail[3] = {};
  for (std::size_t i = rig.poses.size() > 100 ? rig.poses.size() - 100 : 0; i < rig.poses.size();
       ++i) {
    ++tail[rig.poses[i].station <= 2 ? rig.poses[i].station : 0];
  }
  EXPECT_GT(tail[1], 30u);
  EXPECT_GT(tail[2], 30u);
}

TEST_P(LibertySession, TheWrongModelIsRefusedItsListsAndNeverStreams) {
  // A Fastrak session on a Liberty-family unit (and the reverse): the unit does not
  // answer the other's start-up (the Liberty reads lines up to CR, so a Fastrak's `S` is
  // never a command; a Fastrak refuses `F0`, answers ^V with an error record, not a WhoAmI
  // line), so the session keeps re-initialising; no pose is ever taken.
  for (const bool session_is_fastrak : {true, false}) {
    SCOPED_TRACE(session_is_fastrak ? "fastrak session" : "frame session");
    Rig rig(kMotion, session_is_fastrak ? TrackerModel::fastrak : GetParam(),
            session_is_fastrak ? GetParam() : TrackerModel::fastrak);
    rig.run(5.0);
    EXPECT_TRUE(rig.poses.empty());
    const auto& c = rig.session.counters();
    EXPECT_GE(c.status_timeouts + c.status_mismatch, 1u);
    EXPECT_GE(c.inits, 2u);
  }
}

TEST_P(LibertySession, NeedsBinaryOutput) {
  ::twister::test::FakeClock clock{0};
  SimFastrakStream stream(clock, {}, scenario(kMotion));
  auto cfg = session_config(GetParam());
  cfg.protocol.format = Format::ascii;
  tracker::FastrakSession ascii(stream, clock, cfg);
  EXPECT_EQ(ascii.poll().status().code(), StatusCode::invalid_argument);
  cfg.protocol.format = Format::binary16;
  tracker::FastrakSession packed(stream, clock, cfg);
  EXPECT_EQ(packed.poll().status().code(), StatusCode::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Models, LibertySession,
                         ::testing::Values(TrackerModel::liberty, TrackerModel::patriot),
                         [](const auto& param_info) {
                           return std::string(tracker::tracker_model_name(param_info.param));
                         });

}  // namespace
}  // namespace twister::sim
