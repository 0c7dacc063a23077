// twister-sim --buttons without GPIO: the spec (mirroring the station's [buttons.gpiod])
// and ButtonPlayer, which plays the scenario's button lines on the device's clock.
#include "gpio_buttons.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace twister::sim {
namespace {

TEST(GpioButtonsSpec, ChipOffsetsAndLevel) {
  auto s = parse_gpio_buttons("gpiod:gpiochip1:17,27,22");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->chip, "gpiochip1");
  EXPECT_EQ(s->lines, (std::vector<std::uint32_t>{17, 27, 22}));
  EXPECT_TRUE(s->active_low);  // like the station's default
  EXPECT_FALSE(s->open_drain);
  s = parse_gpio_buttons("gpiod:/dev/gpiochip0:4:active-high:open-drain");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->chip, "/dev/gpiochip0");
  EXPECT_FALSE(s->active_low);
  EXPECT_TRUE(s->open_drain);
}

TEST(GpioButtonsSpec, RefusesWhatIsNotAWiring) {
  for (const char* bad :
       {"gpiochip0:1,2", "gpiod:gpiochip0", "gpiod::1", "gpiod:c:1,,2", "gpiod:c:1,x", "gpiod:c:-1",
        "gpiod:c:1024", "gpiod:c:3,3", "gpiod:c:1:sideways",
        "gpiod:c:0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16"}) {
    const auto s = parse_gpio_buttons(bad);
    ASSERT_FALSE(s) << bad;
    EXPECT_EQ(s.error().status.code(), StatusCode::invalid_argument) << bad;
    EXPECT_NE(s.error().message.find("expected gpiod:CHIP:OFFSET"), std::string::npos)
        << s.error().message;
  }
}

TEST(ButtonPlayer, EveryScriptedLineMustBeWired) {
  const ButtonPlayer player({{1.0, 0, true}, {1.0, 3, true}});
  EXPECT_TRUE(player.check_lines(4));
  const auto unwired = player.check_lines(3);
  ASSERT_FALSE(unwired);
  EXPECT_NE(unwired.error().message.find("button line 3"), std::string::npos);
}

// Events play at their scripted time (rounded to the microsecond) on the clock given,
// oldest first; an event that does not change its line is no edge.
TEST(ButtonPlayer, PlaysEdgesWhenDue) {
  ButtonPlayer player({{2.5, 0, true}, {2.5, 3, true}, {3.0, 3, true}, {5.5, 0, false}});
  std::vector<std::pair<std::size_t, bool>> set;
  const auto record = [&](std::size_t line, bool pressed) {
    set.emplace_back(line, pressed);
    return ok_status();
  };
  ASSERT_TRUE(player.advance(2'499'999, record).ok());
  EXPECT_TRUE(set.empty());
  ASSERT_TRUE(player.advance(2'500'000, record).ok());
  EXPECT_EQ(set, (std::vector<std::pair<std::size_t, bool>>{{0, true}, {3, true}}));
  ASSERT_TRUE(player.advance(5'000'000, record).ok());  // line 3 pressed again: no edge
  EXPECT_EQ(set.size(), 2u);
  EXPECT_EQ(player.remaining(), 1u);
  ASSERT_TRUE(player.advance(9'000'000, record).ok());
  EXPECT_EQ(set.back(), (std::pair<std::size_t, bool>{0, false}));
  EXPECT_EQ(player.edges(), 3u);
  EXPECT_EQ(player.remaining(), 0u);
}

TEST(ButtonPlayer, AFailedLineStopsThePlay) {
  ButtonPlayer player({{0.0, 0, true}, {0.0, 1, true}});
  int calls = 0;
  const Status s = player.advance(1, [&](std::size_t, bool) {
    ++calls;
    return Status(StatusCode::io_error);
  });
  EXPECT_EQ(s.code(), StatusCode::io_error);
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace twister::sim
