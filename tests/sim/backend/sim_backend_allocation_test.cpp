// The in-process simulator backend in steady state allocates nothing: the Fastrak
// model generating and pacing records for two receivers (with stylus presses),
// SimFastrakStream handing them to a real FastrakSession, SimButtonSource playing
// scripted presses. Start-up (commands, replies) may allocate; after it, nothing.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "allocation_counter.hpp"
#include "twister/sim/sim_button_source.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#include "twister/sim/virtual_clock.hpp"
#include "twister/tracker/fastrak_session.hpp"

namespace twister::sim {
namespace {

using tracker::Item;
using tracker::OutputList;

// Both receivers circle; the stylus is pressed every second; button lines 0 and 3
// (both hands' grab) go down and up every two seconds.
std::string busy_scenario() {
  std::string text = "seed 7\nreceivers 2\nduration 14\ncircle 2 10 6 4 3 2\n";
  for (int s = 0; s <= 14; ++s) {
    text += "key " + std::to_string(s) + " 1 10 -6 4 " + std::to_string(10 * s) + " 0 0 " +
            std::to_string(s % 2) + "\n";
  }
  for (int s = 1; s < 14; s += 2) {
    text += "button " + std::to_string(s) + " 0 1\nbutton " + std::to_string(s) + " 3 1\n";
    text += "button " + std::to_string(s + 1) + " 0 0\nbutton " + std::to_string(s + 1) + " 3 0\n";
  }
  return text;
}

tracker::FastrakSessionConfig session_config() {
  tracker::FastrakSessionConfig c;
  c.protocol.format = tracker::Format::ascii;
  for (std::size_t s = 0; s < 2; ++s) {
    c.protocol.stations[s].enabled = true;
    c.protocol.stations[s].list =
        OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf});
  }
  c.ladder_char_pause_us = 20'000;
  c.reset_wait_us = 600'000;
  c.settle_us = 50'000;
  c.reply_timeout_us = 300'000;
  c.command_pause_us = 50'000;  // the simulator's default command times (40 ms)
  return c;
}

TEST(SimBackendAllocation, StreamingTwoReceiversWithButtonsAllocatesNothing) {
  VirtualClock clock(1'000'000);
  Scenario sc;
  std::string err;
  ASSERT_TRUE(parse_scenario(busy_scenario(), sc, err)) << err;
  SimButtonSource buttons(clock, sc.buttons, clock.now_us(), 6);
  SimFastrakStream stream(clock, FastrakDeviceConfig{}, sc);
  tracker::FastrakSession session(stream, clock, session_config());

  std::size_t poses = 0;
  std::size_t edges = 0;
  std::size_t stylus_downs = 0;
  const auto run_for = [&](double seconds) {
    const auto end = clock.now_us() + static_cast<ports::TimestampUs>(seconds * 1e6);
    while (clock.now_us() < end) {
      for (auto p = session.poll(); p.ok(); p = session.poll()) {
        ++poses;
        stylus_downs += p->button ? 1 : 0;
      }
      for (auto e = buttons.poll(); e.ok(); e = buttons.poll()) ++edges;
      clock.advance_us(1'000);
    }
  };
  // Start-up: the session configures the unit (commands allocate); 11 commands at the
  // unit's 40 ms processing time take 0.55 s of it.
  run_for(3.0);
  ASSERT_TRUE(session.streaming());
  const std::size_t poses_before = poses;
  test::AllocationCounter counter;
  run_for(11.0);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(session.streaming());
  // 120 Hz shared by two receivers for 11 s; presses came through both paths.
  EXPECT_GT(poses - poses_before, 1300u);
  EXPECT_GT(stylus_downs, 100u);
  EXPECT_GE(edges, 20u);
  EXPECT_EQ(stream.device().counters().line_overflow, 0u);
}

// The fidelity paths in steady state: both filters on, in-record corruption, a short
// baud mismatch, scripted status letters, a line hit and noise. None makes the
// session re-initialise, so nothing may allocate after start-up.
TEST(SimBackendAllocation, FiltersCorruptionMisclockAndStatusLettersAllocateNothing) {
  VirtualClock clock(1'000'000);
  Scenario sc;
  std::string err;
  ASSERT_TRUE(parse_scenario(busy_scenario() +
                                 "fault 4 corrupt 300\nfault 6 wrongbaud 0.3\n"
                                 "fault 7 drop 40\nfault 8 noise 200\nstatus 5 2 E 2\n",
                             sc, err))
      << err;
  FastrakDeviceConfig dev;
  dev.start_position_filter = dev.start_attitude_filter = kFilterMedium;
  SimFastrakStream stream(clock, dev, sc);
  tracker::FastrakSession session(stream, clock, session_config());
  std::size_t poses = 0;
  const auto run_for = [&](double seconds) {
    const auto end = clock.now_us() + static_cast<ports::TimestampUs>(seconds * 1e6);
    while (clock.now_us() < end) {
      for (auto p = session.poll(); p.ok(); p = session.poll()) ++poses;
      clock.advance_us(1'000);
    }
  };
  run_for(3.0);
  ASSERT_TRUE(session.streaming());
  test::AllocationCounter counter;
  run_for(9.0);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(session.streaming());
  EXPECT_EQ(session.counters().streams_started, 1u);
  const auto& c = stream.device().counters();
  EXPECT_EQ(c.corrupted_records, 300u);
  EXPECT_GT(c.misclock_lost, 0u);
  EXPECT_GT(c.status_letters, 100u);
  EXPECT_GT(poses, 900u);
}

}  // namespace
}  // namespace twister::sim
