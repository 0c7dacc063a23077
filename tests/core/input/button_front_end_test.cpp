#include "twister/input/button_front_end.hpp"

#include <gtest/gtest.h>

namespace twister::input {
namespace {

ButtonDebouncerConfig debounce_us(ports::TimestampUs interval_us) {
  ButtonDebouncerConfig c;
  for (auto& i : c.interval_us) i = interval_us;
  return c;
}

TEST(ButtonFrontEnd, DebouncedPressReachesTheMappedRoleOfTheHand) {
  ButtonFrontEnd b(debounce_us(5'000), ButtonMap::paper_default());
  ASSERT_TRUE(b.feed({5, true, 1'000}).ok());  // line 5: hand 1 freeze
  b.poll(3'500);                               // half the interval: not yet
  EXPECT_FALSE(b.hand(1).freeze);
  b.poll(6'000);
  EXPECT_TRUE(b.hand(1).freeze);
  EXPECT_FALSE(b.hand(1).grab);
  EXPECT_FALSE(b.hand(0).freeze);
}

TEST(ButtonFrontEnd, LevelsStayUntilTheNextPoll) {
  ButtonFrontEnd b(debounce_us(0), ButtonMap::paper_default());
  ASSERT_TRUE(b.feed({0, true, 0}).ok());
  EXPECT_FALSE(b.hand(0).grab);  // fed, not polled
  b.poll(0);
  EXPECT_TRUE(b.hand(0).grab);
  ASSERT_TRUE(b.feed({0, false, 10}).ok());
  EXPECT_TRUE(b.hand(0).grab);
  b.poll(10);
  EXPECT_FALSE(b.hand(0).grab);
}

TEST(ButtonFrontEnd, OnePollAppliesEveryDueChange) {
  ButtonFrontEnd b(debounce_us(0), ButtonMap::paper_default());
  // Every line but the right radius: held with the right freeze it is the paper map's
  // symmetry chord, not the clutch (ButtonMap::paper_default).
  for (const std::uint8_t line : {0, 1, 2, 3, 5}) ASSERT_TRUE(b.feed({line, true, 0}).ok());
  b.poll(0);
  EXPECT_TRUE(b.hand(0).grab && b.hand(0).radius && b.hand(0).move_object);
  EXPECT_TRUE(b.hand(1).grab && !b.hand(1).radius && b.hand(1).freeze);
  EXPECT_FALSE(b.hand(0).freeze);
  EXPECT_FALSE(b.hand(1).move_object);
}

TEST(ButtonFrontEnd, UsesTheGivenMap) {
  ButtonMap map;
  ASSERT_TRUE(map.bind(2, 1, ButtonRole::grab).ok());
  ButtonFrontEnd b(debounce_us(0), map);
  ASSERT_TRUE(b.feed({2, true, 0}).ok());
  ASSERT_TRUE(b.feed({0, true, 0}).ok());  // unbound: ignored
  b.poll(0);
  EXPECT_TRUE(b.hand(1).grab);
  EXPECT_FALSE(b.hand(0).grab);
}

TEST(ButtonFrontEnd, UnknownLineIsOutOfRange) {
  ButtonFrontEnd b(debounce_us(0), ButtonMap::paper_default());
  EXPECT_EQ(b.feed({6, true, 0}).code(), StatusCode::out_of_range);  // 6 lines by default
  b.poll(0);
  EXPECT_FALSE(b.hand(0).grab);
  EXPECT_FALSE(b.hand(1).grab);
}

}  // namespace
}  // namespace twister::input
