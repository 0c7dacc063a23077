#include "twister/input/button_map.hpp"

#include <gtest/gtest.h>

namespace twister::input {
namespace {

TEST(ButtonMap, PaperDefaultHasThreeButtonsPerHand) {
  const ButtonMap m = ButtonMap::paper_default();
  EXPECT_EQ(m.binding(0).role, ButtonRole::grab);
  EXPECT_EQ(m.binding(0).hand, 0);
  EXPECT_EQ(m.binding(1).role, ButtonRole::radius);
  EXPECT_EQ(m.binding(2).role, ButtonRole::move_object);
  EXPECT_EQ(m.binding(3).role, ButtonRole::grab);
  EXPECT_EQ(m.binding(3).hand, 1);
  EXPECT_EQ(m.binding(4).role, ButtonRole::radius);
  EXPECT_EQ(m.binding(5).role, ButtonRole::freeze);
  EXPECT_EQ(m.binding(6).role, ButtonRole::none);
}

TEST(ButtonMap, ApplySetsAndClearsTheMappedLevel) {
  const ButtonMap m = ButtonMap::paper_default();
  std::array<HandButtons, kHandCount> levels{};
  m.apply({5, true, 0}, levels);
  EXPECT_TRUE(levels[1].freeze);
  EXPECT_FALSE(levels[0].freeze);
  m.apply({5, false, 1}, levels);
  EXPECT_FALSE(levels[1].freeze);
  m.apply({9, true, 2}, levels);  // unbound: no effect
  EXPECT_FALSE(levels[0].grab || levels[1].grab);
}

TEST(ButtonMap, RebindingIsConfigurable) {
  ButtonMap m;
  ASSERT_TRUE(m.bind(7, 1, ButtonRole::move_object).ok());
  EXPECT_EQ(m.bind(16, 0, ButtonRole::grab).code(), StatusCode::out_of_range);
  EXPECT_EQ(m.bind(0, 2, ButtonRole::grab).code(), StatusCode::out_of_range);
  std::array<HandButtons, kHandCount> levels{};
  m.apply({7, true, 0}, levels);
  EXPECT_TRUE(levels[1].move_object);
}

}  // namespace
}  // namespace twister::input
