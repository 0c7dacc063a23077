// The simulator's departures from a real unit found by running VRPN's Fastrak driver
// against twister-sim (issue 22), each now modelled, in virtual time:
//  - two stations at 19,200 baud with VRPN's 32-byte list both report, in proportion;
//  - input arriving while a command is processed waits in the input buffer (bounded:
//    an overrun loses bytes), so commands sent back to back are all executed;
//  - a stylus press in polled mode acts as `P` (the default `e1,1`);
//  - a hang-up (the adapter pulled) leaves the unit streaming in its configuration;
//  - the scenario's clock can start at the host's first `C`.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "device_host.hpp"

namespace twister::sim {
namespace {

using tracker::EventKind;
using tracker::FastrakEvent;
using tracker::Format;
using tracker::Item;
using tracker::OutputList;

FastrakDeviceConfig quick_device() {
  FastrakDeviceConfig d;
  d.reset_time_us = 0;
  return d;
}

using Host = test::DeviceHost;

// VRPN's list (vrpn_Tracker_Fastrak: "O%d,2,11,0"): 3 + 12 + 16 + 1 = 32 bytes in binary,
// 320 bit times: exactly two 120 Hz cycles at 19,200 baud.
const OutputList kVrpnList = OutputList::of({Item::position, Item::quaternion, Item::space});

tracker::FastrakConfig two_stations(Format f, OutputList l) {
  tracker::FastrakConfig c;
  c.format = f;
  c.stations[0] = {true, l};
  c.stations[1] = {true, l};
  return c;
}

std::array<int, 3> poses_per_station(const std::vector<FastrakEvent>& ev) {
  std::array<int, 3> n{};
  for (const auto& e : ev) {
    if (e.kind == EventKind::pose && e.pose.station <= 2) ++n[e.pose.station];
  }
  return n;
}

TEST(FastrakDeviceDepartures, TwoStationsAt19200BaudBothReportInProportion) {
  FastrakDeviceConfig dev = quick_device();
  dev.baud = 19200;
  dev.command_time_us = instant_commands();
  Host h("receivers 2\n", dev);
  h.send("O1,2,11,0\rO2,2,11,0\rfC");
  h.run(0.1);
  h.out.clear();
  h.run(3.0);
  const auto n = poses_per_station(h.events(two_stations(Format::binary, kVrpnList)));
  std::printf(
      "[19200 baud, two stations, 3 s] station 1: %d, station 2: %d records; "
      "dropped solutions %llu\n",
      n[1], n[2], static_cast<unsigned long long>(h.device.counters().dropped_solutions));
  // Each record holds the line for two cycles and a bit: one in three cycles is sent,
  // alternating stations, 20 records per second each.
  EXPECT_GE(n[2], 55);
  EXPECT_LE(std::abs(n[1] - n[2]), 1);
  EXPECT_GE(n[1] + n[2], 115);
  EXPECT_LE(n[1] + n[2], 125);
}

TEST(FastrakDeviceDepartures, TwoStationsAtLineRatesThatKeepUpStillAlternate) {
  // At 115,200 baud the record takes a third of a cycle: 60 records a second each.
  FastrakDeviceConfig dev = quick_device();
  dev.command_time_us = instant_commands();
  Host h("receivers 2\n", dev);
  h.send("O1,2,11,0\rO2,2,11,0\rfC");
  h.run(0.1);
  h.out.clear();
  h.run(2.0);
  const auto n = poses_per_station(h.events(two_stations(Format::binary, kVrpnList)));
  EXPECT_NEAR(n[1], 120, 1);
  EXPECT_NEAR(n[2], 120, 1);
  EXPECT_EQ(h.device.counters().dropped_solutions, 0u);
}

TEST(FastrakDeviceDepartures, CommandsSentBackToBackAreAllExecuted) {
  Host h("receivers 1\n", quick_device());  // default command times: O takes 40 ms
  h.send("O1,2,11,1\rO1\r");                // the read-back arrives while O is processed
  h.run(0.2);
  EXPECT_EQ(h.text(), "21O 211 1\r\n");
  EXPECT_EQ(h.device.counters().commands, 2u);
  EXPECT_EQ(h.device.counters().input_lost, 0u);
  // VRPN's reset ladder and configuration, written without pauses: c, CR c, then the
  // list, binary and status.
  h.out.clear();
  h.send("c\rcO1,2,11,0\rfS");
  h.run(0.2);
  const std::string t = h.text();
  ASSERT_EQ(t.size(), 55u) << t;  // the status, after O's 40 ms
  EXPECT_EQ(t.substr(0, 3), "21S");
  EXPECT_TRUE(h.device.protocol().format == Format::binary);
  EXPECT_EQ(h.device.counters().commands, 7u);
}

TEST(FastrakDeviceDepartures, AFullInputBufferLosesWhatArrivesBeyondIt) {
  Host h("receivers 1\n", quick_device());
  h.send("x\r");  // 500 ms of processing
  h.send(std::string(300, 'F'));
  EXPECT_EQ(h.device.counters().input_lost, 300u - kInputBufferBytes);
  h.run(0.6);
  EXPECT_EQ(h.device.counters().commands, 1u + kInputBufferBytes);
  EXPECT_EQ(h.device.counters().input_lost, 300u - kInputBufferBytes);
}

TEST(FastrakDeviceDepartures, AResetEmptiesTheInputBuffer) {
  FastrakDeviceConfig dev = quick_device();
  dev.reset_time_us = 1'000'000;
  Host h("receivers 1\n", dev);
  h.run(1.1);
  h.send("x\r");                      // busy 500 ms
  h.send(std::string("\x19") + "S");  // ^Y buffered, then S: lost to the reboot
  h.run(0.6);
  EXPECT_EQ(h.device.counters().resets, 2u);
  EXPECT_EQ(h.device.counters().input_lost, 1u);
  h.run(1.5);
  EXPECT_EQ(h.text().find("21S"), std::string::npos);
}

TEST(FastrakDeviceDepartures, WithoutAnInputBufferEarlyCommandsAreLost) {
  FastrakDeviceConfig dev = quick_device();
  dev.input_buffer_bytes = 0;
  Host h("receivers 1\n", dev);
  h.send("O1,2,11,1\rO1\r");
  h.run(0.2);
  EXPECT_EQ(h.text(), "");
  EXPECT_EQ(h.device.counters().input_lost, 3u);
}

// Receiver 1's stylus pressed from 1.0 s to 1.5 s and from 2.0 s to 2.5 s.
constexpr const char* kTwoPresses =
    "receivers 2\n"
    "key 0 1 10 -4 2 0 0 0 0\n"
    "key 0.99 1 10 -4 2 0 0 0 0\n"
    "key 1 1 10 -4 2 0 0 0 1\n"
    "key 1.5 1 10 -4 2 0 0 0 0\n"
    "key 1.99 1 10 -4 2 0 0 0 0\n"
    "key 2 1 10 -4 2 0 0 0 1\n"
    "key 2.5 1 10 -4 2 0 0 0 0\n";

TEST(FastrakDeviceDepartures, AStylusPressInPolledModeActsAsP) {
  Host h(kTwoPresses, quick_device());  // powers up polled, e1,1, ASCII, list 2,4,1
  h.run(0.9);
  EXPECT_EQ(h.text(), "");
  h.run(0.3);  // the first press: one record per active station, as `P`
  tracker::FastrakConfig ascii;
  ascii.stations[0].enabled = ascii.stations[1].enabled = true;
  auto n = poses_per_station(h.events(ascii));
  EXPECT_EQ(n[1], 1);
  EXPECT_EQ(n[2], 1);
  h.run(1.0);  // the release does nothing; the second press polls again
  n = poses_per_station(h.events(ascii));
  EXPECT_EQ(n[1], 2);
  EXPECT_EQ(n[2], 2);
  EXPECT_EQ(h.device.counters().output.stylus_polls, 2u);
}

TEST(FastrakDeviceDepartures, InMouseModeAPolledPressSendsNothing) {
  FastrakDeviceConfig dev = quick_device();
  dev.command_time_us = instant_commands();
  Host h(kTwoPresses, dev);
  h.send("e1,0\r");
  h.run(3.0);
  EXPECT_EQ(h.text(), "");
  EXPECT_EQ(h.device.counters().output.stylus_polls, 0u);
}

TEST(FastrakDeviceDepartures, AHangUpLeavesTheUnitStreamingInItsConfiguration) {
  FastrakDeviceConfig dev = quick_device();
  dev.command_time_us = instant_commands();
  Host h("receivers 1\nfault 2 hangup 1\n", dev);
  h.send("O1,2,11,0\ruf");  // VRPN's list, centimetres, binary; then continuous
  h.send("C");
  h.run(1.9);
  ASSERT_FALSE(h.device.hung_up(h.now));
  h.run(0.2);
  EXPECT_TRUE(h.device.hung_up(h.now));
  h.out.clear();
  h.run(1.9);  // to 4.0 s: the line is back at 3.0 s; the host sends nothing
  EXPECT_FALSE(h.device.hung_up(h.now));
  tracker::FastrakConfig cfg;
  cfg.format = Format::binary;
  cfg.units = tracker::Units::centimetres;
  cfg.stations[0] = {true, kVrpnList};
  const auto ev = h.events(cfg);
  const auto n = poses_per_station(ev);
  // Only what was sent after the line came back: about 1 s of 120 Hz records.
  EXPECT_NEAR(n[1], 120, 3);
  for (const auto& e : ev) EXPECT_EQ(e.kind, EventKind::pose);
  EXPECT_TRUE(h.device.continuous());
  EXPECT_EQ(h.device.counters().resets, 1u);  // the power-up only
  EXPECT_GT(h.device.counters().output.hangup_lost, 0u);
}

// x moves from 10 in at t = 0 to 20 in at t = 10 s.
constexpr const char* kSlide =
    "receivers 1\n"
    "key 0 1 10 0 0 0 0 0\n"
    "key 10 1 20 0 0 0 0 0\n"
    "fault 0.5 noise 100\n";

double first_x_after_c(ScenarioClock clock, FastrakDeviceCounters& counters) {
  FastrakDeviceConfig dev = quick_device();
  dev.command_time_us = instant_commands();
  dev.scenario_clock = clock;
  Host h(kSlide, dev);
  h.send("O1,2,11,1\rf");
  h.run(3.0);  // the host's start-up: 3 s before continuous output
  counters = h.device.counters();
  h.out.clear();
  h.send("C");
  h.run(0.05);
  tracker::FastrakConfig cfg;
  cfg.format = Format::binary;
  cfg.stations[0] = {true, OutputList::of({Item::position, Item::quaternion, Item::crlf})};
  for (const auto& e : h.events(cfg)) {
    if (e.kind == EventKind::pose) return e.pose.position[0];
  }
  return -1.0;
}

TEST(FastrakDeviceDepartures, TheScenarioClockCanStartAtTheFirstC) {
  FastrakDeviceCounters before{};
  const double at_power_up = first_x_after_c(ScenarioClock::power_up, before);
  EXPECT_NEAR(at_power_up, 13.0, 0.05);  // 3 s into the slide
  EXPECT_EQ(before.faults[static_cast<std::size_t>(FaultKind::noise)], 1u);
  const double at_c = first_x_after_c(ScenarioClock::first_continuous, before);
  EXPECT_NEAR(at_c, 10.0, 0.05);  // the slide starts with the stream
  EXPECT_EQ(before.faults[static_cast<std::size_t>(FaultKind::noise)], 0u);  // not due yet
}

TEST(FastrakDeviceDepartures, OnTheStreamClockFaultsFallDueAfterTheFirstC) {
  FastrakDeviceConfig dev = quick_device();
  dev.command_time_us = instant_commands();
  dev.scenario_clock = ScenarioClock::first_continuous;
  Host h(kSlide, dev);
  h.run(2.0);
  EXPECT_FALSE(h.device.scenario_started());
  EXPECT_EQ(h.device.scenario_time_s(h.now), 0.0);
  h.send("C");
  EXPECT_TRUE(h.device.scenario_started());
  h.run(0.45);
  EXPECT_EQ(h.device.counters().faults[static_cast<std::size_t>(FaultKind::noise)], 0u);
  h.run(0.1);
  EXPECT_EQ(h.device.counters().faults[static_cast<std::size_t>(FaultKind::noise)], 1u);
  EXPECT_NEAR(h.device.scenario_time_s(h.now), 0.55, 1e-3);
  h.send("cC");  // a later C does not move t = 0
  EXPECT_NEAR(h.device.scenario_time_s(h.now), 0.55, 1e-3);
}

}  // namespace
}  // namespace twister::sim
