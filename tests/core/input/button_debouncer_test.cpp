#include "twister/input/button_debouncer.hpp"

#include <gtest/gtest.h>

namespace twister::input {
namespace {

ButtonDebouncerConfig config_with(ports::TimestampUs line0_us, ports::TimestampUs line1_us) {
  ButtonDebouncerConfig c;
  c.line_count = 2;
  c.interval_us[0] = line0_us;
  c.interval_us[1] = line1_us;
  return c;
}

TEST(ButtonDebouncer, ReportsAtFullIntervalNotAtHalf) {
  ButtonDebouncer d(config_with(10'000, 10'000));
  ASSERT_TRUE(d.feed({0, true, 1'000}).ok());
  EXPECT_EQ(d.poll(1'000 + 5'000).status().code(), StatusCode::unavailable);
  EXPECT_FALSE(d.pressed(0));
  auto e = d.poll(1'000 + 10'000);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 0);
  EXPECT_TRUE(e->pressed);
  EXPECT_EQ(e->time_us, 11'000);
  EXPECT_TRUE(d.pressed(0));
  EXPECT_EQ(d.poll(50'000).status().code(), StatusCode::unavailable);
}

TEST(ButtonDebouncer, BounceInsideIntervalRestartsTheWait) {
  ButtonDebouncer d(config_with(10'000, 10'000));
  ASSERT_TRUE(d.feed({0, true, 0}).ok());
  ASSERT_TRUE(d.feed({0, false, 2'000}).ok());
  ASSERT_TRUE(d.feed({0, true, 4'000}).ok());
  EXPECT_EQ(d.poll(10'000).status().code(), StatusCode::unavailable);  // 6 ms after last edge
  auto e = d.poll(14'000);
  ASSERT_TRUE(e.ok());
  EXPECT_TRUE(e->pressed);
}

TEST(ButtonDebouncer, ShortGlitchIsNeverReported) {
  ButtonDebouncer d(config_with(10'000, 10'000));
  ASSERT_TRUE(d.feed({0, true, 0}).ok());
  ASSERT_TRUE(d.feed({0, false, 3'000}).ok());
  EXPECT_EQ(d.poll(100'000).status().code(), StatusCode::unavailable);
  EXPECT_FALSE(d.pressed(0));
}

TEST(ButtonDebouncer, IntervalIsPerLine) {
  ButtonDebouncer d(config_with(2'000, 20'000));
  ASSERT_TRUE(d.feed({0, true, 0}).ok());
  ASSERT_TRUE(d.feed({1, true, 0}).ok());
  // Half of line 1's interval: line 0 (full interval passed) only.
  auto e = d.poll(10'000);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 0);
  EXPECT_EQ(d.poll(10'000).status().code(), StatusCode::unavailable);
  auto f = d.poll(20'000);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->line, 1);
}

TEST(ButtonDebouncer, ReleaseIsDebouncedToo) {
  ButtonDebouncer d(config_with(10'000, 10'000));
  ASSERT_TRUE(d.feed({0, true, 0}).ok());
  ASSERT_TRUE(d.poll(10'000).ok());
  ASSERT_TRUE(d.feed({0, false, 20'000}).ok());
  EXPECT_EQ(d.poll(25'000).status().code(), StatusCode::unavailable);
  auto e = d.poll(30'000);
  ASSERT_TRUE(e.ok());
  EXPECT_FALSE(e->pressed);
}

TEST(ButtonDebouncer, LineOutOfRangeIsRejected) {
  ButtonDebouncer d(config_with(10'000, 10'000));
  EXPECT_EQ(d.feed({2, true, 0}).code(), StatusCode::out_of_range);
  EXPECT_EQ(d.feed({200, true, 0}).code(), StatusCode::out_of_range);
  EXPECT_FALSE(d.pressed(200));
}

}  // namespace
}  // namespace twister::input
