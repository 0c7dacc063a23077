// SimButtonSource: scripted scenario button events become ButtonSource edges on the
// simulator's clock.
#include "twister/sim/sim_button_source.hpp"

#include <gtest/gtest.h>

#include <string>

#include "twister/sim/scenario.hpp"
#include "twister/sim/virtual_clock.hpp"

namespace twister::sim {
namespace {

Scenario parse(const char* text) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(sim::parse_scenario(text, sc, err)) << err;
  return sc;
}

TEST(SimButtonSource, PlaysEventsWhenTheirTimeComesWithTheScriptedTimestamp) {
  VirtualClock clock(1'000'000);
  const Scenario sc = parse("button 0.5 0 1\nbutton 0.5 3 1\nbutton 2 3 0\n");
  SimButtonSource src(clock, sc.buttons, clock.now_us(), 6);
  EXPECT_EQ(src.line_count(), 6);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
  clock.advance_us(499'999);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
  clock.advance_us(1);
  auto a = src.poll();
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->line, 0);
  EXPECT_TRUE(a->pressed);
  EXPECT_EQ(a->time_us, 1'500'000);
  auto b = src.poll();
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->line, 3);
  EXPECT_TRUE(b->pressed);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
  // Polled late: the edge still carries the scripted time.
  clock.advance_us(5'000'000);
  auto c = src.poll();
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->line, 3);
  EXPECT_FALSE(c->pressed);
  EXPECT_EQ(c->time_us, 3'000'000);
  EXPECT_EQ(src.remaining(), 0u);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
}

TEST(SimButtonSource, RepeatedLevelsAreNotEdges) {
  VirtualClock clock(0);
  const Scenario sc = parse("button 0 1 0\nbutton 1 1 1\nbutton 2 1 1\nbutton 3 1 0\n");
  SimButtonSource src(clock, sc.buttons, 0, 6);
  clock.advance_us(10'000'000);
  auto a = src.poll();
  ASSERT_TRUE(a.ok());
  EXPECT_TRUE(a->pressed);
  EXPECT_EQ(a->time_us, 1'000'000);
  auto b = src.poll();
  ASSERT_TRUE(b.ok());
  EXPECT_FALSE(b->pressed);
  EXPECT_EQ(b->time_us, 3'000'000);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
}

TEST(SimButtonSource, LineCountCoversTheHighestScriptedLine) {
  VirtualClock clock(0);
  const Scenario sc = parse("button 0 9 1\n");
  SimButtonSource src(clock, sc.buttons, 0, 6);
  EXPECT_EQ(src.line_count(), 10);
  auto e = src.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 9);
  SimButtonSource none(clock, {}, 0, 6);
  EXPECT_EQ(none.line_count(), 6);
  EXPECT_EQ(none.poll().status().code(), StatusCode::unavailable);
}

TEST(SimButtonSource, StartOffsetShiftsTheScript) {
  VirtualClock clock(0);
  const Scenario sc = parse("button 1 4 1\n");
  SimButtonSource src(clock, sc.buttons, 2'000'000, 6);
  clock.advance_us(2'999'999);
  EXPECT_EQ(src.poll().status().code(), StatusCode::unavailable);
  clock.advance_us(1);
  auto e = src.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->time_us, 3'000'000);
}

}  // namespace
}  // namespace twister::sim
