// FastrakSession in virtual time against FakeByteStream: start-up sequence, reply
// timeouts and the reset ladder, silence / garbage / unplug detection, re-init with
// back-off, and that only validated poses come out.
#include "twister/tracker/fastrak_session.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "allocation_counter.hpp"
#include "fakes/fake_byte_stream.hpp"
#include "fakes/fake_clock.hpp"
#include "tracker_test_util.hpp"
#include "twister/tracker/fastrak_encoder.hpp"

namespace twister::tracker {
namespace {

using test::f32le;

FastrakSessionConfig fast_config() {
  FastrakSessionConfig c;
  c.protocol = test::one_station(Format::binary,
                                 OutputList::of({Item::position, Item::quaternion, Item::crlf}));
  c.ladder_char_pause_us = 1'000;
  c.reset_wait_us = 50'000;
  c.settle_us = 2'000;
  c.reply_timeout_us = 20'000;
  c.command_pause_us = 500;
  c.backoff.initial_us = 10'000;
  c.backoff.max_us = 80'000;
  return c;
}

std::string status_reply(bool binary, bool cm = false, bool continuous = false) {
  std::array<std::byte, 64> buf{};
  FastrakStatus s;
  s.station = 1;
  s.flags = 0x3F0;
  s.binary = binary;
  s.centimetres = cm;
  s.continuous = continuous;
  auto n = encode_status(s, buf);
  return std::string(reinterpret_cast<const char*>(buf.data()), *n);
}

std::string record(float x, float q0 = 1.0f) {
  std::string r =
      "01 " + f32le(x) + f32le(2) + f32le(3) + f32le(q0) + f32le(0) + f32le(0) + f32le(0);
  return r + "\r\n";
}

struct Rig {
  ::twister::test::FakeByteStream stream;
  ::twister::test::FakeClock clock{1000000};
  FastrakSession session;
  std::vector<FastrakPose> poses;

  explicit Rig(const FastrakSessionConfig& c = fast_config()) : session(stream, clock, c) {}

  void poll_all() {
    for (auto p = session.poll(); p.ok(); p = session.poll()) poses.push_back(*p);
  }
  // Advances virtual time in steps until pred() holds; false after max_us.
  bool run_until(const std::function<bool()>& pred, std::int64_t max_us,
                 std::int64_t step_us = 250) {
    for (std::int64_t t = 0; t <= max_us; t += step_us) {
      poll_all();
      if (pred()) return true;
      clock.advance_us(step_us);
    }
    return false;
  }
  bool reach(SessionState s, std::int64_t max_us = 500'000) {
    return run_until([&] { return session.state() == s; }, max_us);
  }
  // Plays the device's part of a start-up.
  void start_streaming() {
    ASSERT_TRUE(reach(SessionState::await_status));
    stream.push_rx(status_reply(false));
    ASSERT_TRUE(reach(SessionState::verify_status));
    stream.push_rx(status_reply(true));
    ASSERT_TRUE(reach(SessionState::streaming));
  }
};

TEST(FastrakSession, StartUpSequenceSendsTheSpecCommands) {
  Rig rig;
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  EXPECT_EQ(rig.stream.tx(), "cS");  // rung 1: leave continuous mode, then status
  rig.stream.clear_tx();
  rig.stream.push_rx(status_reply(false));
  ASSERT_TRUE(rig.reach(SessionState::verify_status));
  EXPECT_EQ(rig.stream.tx(), "l1,1\rO1,2,11,1\rH1,1,0,0\rl2,0\rl3,0\rl4,0\re1,0\rUfS");
  rig.stream.clear_tx();
  rig.stream.push_rx(status_reply(true));
  ASSERT_TRUE(rig.reach(SessionState::streaming));
  EXPECT_EQ(rig.stream.tx(), "C");
  rig.stream.push_rx(record(10) + record(11));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 2u);
  EXPECT_EQ(rig.poses[1].position[0], 11.0f);
  EXPECT_EQ(rig.session.counters().streams_started, 1u);
}

TEST(FastrakSession, PosesBeforeStreamingAreNotEmitted) {
  Rig rig;
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  rig.stream.push_rx(record(1) + status_reply(false));
  ASSERT_TRUE(rig.reach(SessionState::verify_status));
  EXPECT_TRUE(rig.poses.empty());
}

TEST(FastrakSession, StatusTimeoutClimbsTheResetLadder) {
  Rig rig;
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  rig.stream.clear_tx();
  ASSERT_TRUE(rig.run_until([&] { return rig.session.ladder_rung() == 2; }, 100'000));
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  EXPECT_EQ(rig.stream.tx(), "\rcS");
  rig.stream.clear_tx();
  ASSERT_TRUE(rig.run_until([&] { return rig.session.ladder_rung() == 3; }, 100'000));
  // Rung 3 adds ^Y and waits reset_wait_us before asking for status.
  ASSERT_TRUE(rig.reach(SessionState::settle, 100'000));
  EXPECT_EQ(rig.stream.tx(), "\rc\x19");
  EXPECT_EQ(rig.session.counters().status_timeouts, 2u);
  // Past the top rung: back-off, reopen, and the ladder again from the top rung.
  ASSERT_TRUE(rig.run_until([&] { return rig.session.counters().status_timeouts == 3; }, 200'000));
  EXPECT_EQ(rig.session.state(), SessionState::backoff);
  rig.stream.clear_tx();
  ASSERT_TRUE(rig.reach(SessionState::await_status, 200'000));
  EXPECT_EQ(rig.stream.tx(), "\rc\x19S");
  EXPECT_GE(rig.stream.reopen_count(), 2);
  // The unit answers at last.
  rig.stream.push_rx(status_reply(false));
  ASSERT_TRUE(rig.reach(SessionState::verify_status));
  rig.stream.push_rx(status_reply(true));
  ASSERT_TRUE(rig.reach(SessionState::streaming));
  EXPECT_EQ(rig.session.ladder_rung(), 0);
}

TEST(FastrakSession, SilenceTriggersReinitialisation) {
  Rig rig;
  rig.start_streaming();
  rig.stream.push_rx(record(5));
  rig.poll_all();
  const int reopens = rig.stream.reopen_count();
  rig.clock.advance_us(2'000'000);
  rig.poll_all();
  EXPECT_EQ(rig.session.state(), SessionState::streaming);  // exactly 2 s: not yet
  rig.clock.advance_us(1);
  rig.poll_all();
  EXPECT_EQ(rig.session.state(), SessionState::backoff);
  EXPECT_EQ(rig.session.counters().silence_faults, 1u);
  rig.start_streaming();
  EXPECT_EQ(rig.stream.reopen_count(), reopens + 1);
  EXPECT_EQ(rig.session.counters().streams_started, 2u);
}

// A host that stalls longer than the silence timeout (a slow fsync, a starved
// process) while the unit keeps sending: the records that came meanwhile are read
// before silence is judged, so the stream is not called lost.
TEST(FastrakSession, AStalledHostFindsTheRecordsThatCameMeanwhile) {
  Rig rig;
  rig.start_streaming();
  rig.stream.push_rx(record(5));
  rig.poll_all();
  rig.clock.advance_us(3'000'000);
  rig.stream.push_rx(record(6));
  rig.poll_all();
  EXPECT_EQ(rig.session.state(), SessionState::streaming);
  EXPECT_EQ(rig.session.counters().silence_faults, 0u);
  EXPECT_EQ(rig.session.counters().garbage_faults, 0u);
  ASSERT_FALSE(rig.poses.empty());
  EXPECT_FLOAT_EQ(rig.poses.back().position[0], 6.0f);
}

TEST(FastrakSession, EndlessGarbageIsDetected) {
  Rig rig;
  rig.start_streaming();
  // Bytes keep coming but none forms a valid record.
  ASSERT_TRUE(rig.run_until(
      [&] {
        rig.stream.push_rx("garbage\x01\x7f 0 1 2 garbage");
        return rig.session.state() != SessionState::streaming;
      },
      3'000'000, 10'000));
  EXPECT_EQ(rig.session.counters().garbage_faults, 1u);
  EXPECT_EQ(rig.session.counters().silence_faults, 0u);
  EXPECT_GT(rig.session.parser_counters().dropped_bytes, 1000u);
  EXPECT_TRUE(rig.poses.empty());
}

TEST(FastrakSession, UnplugAndReplugWithBackoff) {
  Rig rig;
  rig.start_streaming();
  rig.stream.unplug();
  rig.stream.set_present(false);
  rig.poll_all();
  EXPECT_EQ(rig.session.state(), SessionState::backoff);
  EXPECT_EQ(rig.session.counters().io_errors, 1u);
  // Absent for 300 ms: reopen fails with growing delays (10, 20, 40, 80, 80 ms).
  rig.run_until([] { return false; }, 300'000, 1'000);
  const auto failures = rig.session.counters().io_errors;
  EXPECT_GE(failures, 4u);
  EXPECT_LE(failures, 7u);
  rig.stream.set_present(true);
  rig.start_streaming();
  rig.stream.push_rx(record(7));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 1u);
}

// A port that reports its device's arrival (USB hot-plug) is reopened at once, however
// long the back-off had grown, and the back-off starts afresh.
TEST(FastrakSession, ADeviceArrivalEndsTheBackOffAtOnce) {
  Rig rig;
  rig.start_streaming();
  rig.stream.unplug();
  rig.stream.set_present(false);
  rig.run_until([] { return false; }, 300'000, 1'000);  // the back-off is at its cap (80 ms)
  // Just after a failed reopen: the next one is 80 ms away.
  const int before = rig.stream.reopen_count();
  ASSERT_TRUE(rig.run_until([&] { return rig.stream.reopen_count() > before; }, 100'000, 1'000));
  const int reopens = rig.stream.reopen_count();
  rig.stream.set_present(true);
  rig.clock.advance_us(1'000);
  rig.poll_all();
  EXPECT_EQ(rig.stream.reopen_count(), reopens) << "no arrival: the back-off runs on";
  EXPECT_EQ(rig.session.state(), SessionState::backoff);
  rig.stream.announce_arrival();
  rig.poll_all();
  EXPECT_EQ(rig.stream.reopen_count(), reopens + 1);
  EXPECT_NE(rig.session.state(), SessionState::backoff);
  // Unplugged again before streaming: the next delay is the first one again (10 ms).
  rig.stream.unplug();
  rig.stream.set_present(false);
  rig.poll_all();
  ASSERT_EQ(rig.session.state(), SessionState::backoff);
  rig.clock.advance_us(9'000);
  rig.poll_all();
  EXPECT_EQ(rig.stream.reopen_count(), reopens + 1);
  rig.clock.advance_us(1'500);
  rig.poll_all();
  EXPECT_EQ(rig.stream.reopen_count(), reopens + 2);
}

TEST(FastrakSession, StatusMismatchAfterConfiguringIsAFault) {
  Rig rig;
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  rig.stream.push_rx(status_reply(false));
  ASSERT_TRUE(rig.reach(SessionState::verify_status));
  rig.stream.push_rx(status_reply(false));  // still ASCII: `f` was not taken
  rig.poll_all();
  EXPECT_EQ(rig.session.state(), SessionState::backoff);
  EXPECT_EQ(rig.session.counters().status_mismatch, 1u);
}

TEST(FastrakSession, CommandErrorDuringConfigurationIsAFault) {
  Rig rig;
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  rig.stream.push_rx(status_reply(false));
  ASSERT_TRUE(rig.reach(SessionState::configuring));
  rig.stream.push_rx("2 E*ERROR* O1,2,11,1 *ERROR* EC -3 *PS 4 *FL 2 *ST 0\r\n");
  ASSERT_TRUE(rig.reach(SessionState::backoff));
  EXPECT_EQ(rig.session.counters().command_errors, 1u);
}

TEST(FastrakSession, ImplausiblePosesNeverReachTheCaller) {
  Rig rig;
  rig.start_streaming();
  rig.stream.push_rx(record(1) + record(500) + record(2, 0.5f) + "noise" + record(3));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 2u);
  EXPECT_EQ(rig.poses[0].position[0], 1.0f);
  EXPECT_EQ(rig.poses[1].position[0], 3.0f);
  EXPECT_EQ(rig.session.counters().rejected_poses, 2u);
  EXPECT_EQ(rig.session.parser_counters().resyncs, 1u);
}

TEST(FastrakSession, FilterCommandsAreSentAndFollowedByTheFilterPause) {
  FastrakSessionConfig c = fast_config();
  c.position_filter.mode = FilterSetting::Mode::set;  // the manual's "medium"
  c.attitude_filter.mode = FilterSetting::Mode::off;
  c.filter_pause_us = 100'000;
  Rig rig(c);
  ASSERT_TRUE(rig.reach(SessionState::await_status));
  rig.stream.clear_tx();
  rig.stream.push_rx(status_reply(false));
  ASSERT_TRUE(
      rig.run_until([&] { return rig.stream.tx().find('x') != std::string::npos; }, 100'000));
  const auto sent_x = rig.clock.now_us();
  ASSERT_TRUE(
      rig.run_until([&] { return rig.stream.tx().find('v') != std::string::npos; }, 300'000));
  EXPECT_GE(rig.clock.now_us() - sent_x, 100'000);  // nothing sent while the unit filters
  ASSERT_TRUE(rig.reach(SessionState::verify_status, 500'000));
  EXPECT_EQ(
      rig.stream.tx(),
      "l1,1\rO1,2,11,1\rH1,1,0,0\rl2,0\rl3,0\rl4,0\rx0.200,0.200,0.800,0.950\rv,1\re1,0\rUfS");
}

TEST(FastrakSession, Binary16IsSelectedWithSmallFAndChecksTheBinaryFlag) {
  FastrakSessionConfig c = fast_config();
  c.protocol.format = Format::binary16;
  Rig rig(c);
  rig.start_streaming();  // verify_status answers "binary"
  EXPECT_NE(rig.stream.tx().find("Uf"), std::string::npos);
  FastrakPose p;
  p.station = 1;
  p.position = {10.0f, 2.0f, 3.0f};
  p.quaternion = {1.0f, 0.0f, 0.0f, 0.0f};
  std::array<std::byte, 64> buf{};
  auto n = encode_record(p, c.protocol, buf);
  ASSERT_TRUE(n.ok());
  rig.stream.push_rx(std::string(reinterpret_cast<const char*>(buf.data()), *n));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 1u);
  EXPECT_NEAR(rig.poses[0].position[0], 10.0f, 0.002f);
}

TEST(FastrakSession, JumpsAreHeldBackUnlessTheNextPoseConfirmsThem) {
  Rig rig;
  rig.start_streaming();
  // 10 -> 60 in within one cycle is a corrupted value: held back; 10.1 follows the
  // track. Then a real move to 200 in (e.g. a hemisphere flip) is confirmed by two
  // more records agreeing with it and accepted from the third on.
  rig.stream.push_rx(record(10) + record(60) + record(10.1f) + record(200) + record(200.1f) +
                     record(200.2f) + record(200.3f));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 4u);
  EXPECT_EQ(rig.poses[0].position[0], 10.0f);
  EXPECT_EQ(rig.poses[1].position[0], 10.1f);
  EXPECT_EQ(rig.poses[2].position[0], 200.2f);
  EXPECT_EQ(rig.poses[3].position[0], 200.3f);
  EXPECT_EQ(rig.session.counters().jump_rejects, 3u);
  // Time widens the limit: 1.9 s later a 180 in move is within 150 in/s.
  rig.clock.advance_us(1'900'000);
  rig.stream.push_rx(record(20.0f));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 5u);
}

TEST(FastrakSession, StatusLettersAreWarningsThePoseIsUsed) {
  Rig rig;
  rig.start_streaming();
  std::string warn = record(5);
  warn[2] = 'y';  // outside the Q envelope
  std::string weak = record(5.1f);
  weak[2] = 'E';
  rig.stream.push_rx(warn + weak + record(5.2f));
  rig.poll_all();
  ASSERT_EQ(rig.poses.size(), 3u);
  EXPECT_EQ(rig.poses[0].status, 'y');
  EXPECT_EQ(rig.poses[1].status, 'E');
  EXPECT_EQ(rig.session.counters().warning_poses, 2u);
  EXPECT_EQ(rig.session.counters().last_warning, 'E');
}

TEST(FastrakSession, InvalidConfigurationSendsNothing) {
  FastrakSessionConfig c = fast_config();
  c.protocol.stations[0].enabled = false;
  Rig rig(c);
  EXPECT_EQ(rig.session.poll().status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(rig.stream.tx(), "");
}

TEST(FastrakSession, NoHeapAllocationWhileStreaming) {
  Rig rig;
  rig.start_streaming();
  const std::string recs = record(1) + record(2) + "x" + record(3);
  std::size_t n = 0;
  EXPECT_NO_ALLOCATIONS({
    for (int i = 0; i < 100; ++i) {
      rig.stream.push_rx(recs);
      for (auto p = rig.session.poll(); p.ok(); p = rig.session.poll()) ++n;
      rig.clock.advance_us(8'333);
    }
  });
  EXPECT_EQ(n, 300u);
}

}  // namespace
}  // namespace twister::tracker
