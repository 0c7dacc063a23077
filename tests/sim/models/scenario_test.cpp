// Scenario text format: keys, circles, faults, and clear errors naming the line.
#include "twister/sim/scenario.hpp"

#include <gtest/gtest.h>

namespace twister::sim {
namespace {

TEST(Scenario, ParsesAndSamples) {
  Scenario sc;
  std::string err;
  ASSERT_TRUE(
      parse_scenario("# demo\nseed 3\nreceivers 1\nduration 5\n"
                     "key 0 1 10 0 0 0 0 0\nkey 2 1 20 4 0 90 0 0 1  # press\n"
                     "circle 2 0 10 0 5 4\nfault 3 stall 1.5\nfault 1 noise 20\n",
                     sc, err))
      << err;
  EXPECT_EQ(sc.seed, 3u);
  EXPECT_EQ(sc.receivers, 1);
  ASSERT_EQ(sc.faults.size(), 2u);
  EXPECT_EQ(sc.faults[0].kind, FaultKind::noise);  // sorted by time
  const HandSample mid = sample(sc, 1, 1.0);
  EXPECT_DOUBLE_EQ(mid.position_in[0], 15.0);
  EXPECT_DOUBLE_EQ(mid.euler_deg[0], 45.0);
  EXPECT_FALSE(mid.button);
  EXPECT_TRUE(sample(sc, 1, 3.0).button);
  const HandSample c = sample(sc, 2, 1.0);  // quarter turn
  EXPECT_NEAR(c.position_in[0], 0.0, 1e-9);
  EXPECT_NEAR(c.position_in[1], 15.0, 1e-9);
}

TEST(Scenario, ErrorsNameTheLine) {
  Scenario sc;
  std::string err;
  EXPECT_FALSE(parse_scenario("seed 1\nkey 0 9 1 2 3 0 0 0\n", sc, err));
  EXPECT_EQ(err, "line 2: station must be 1..4");
  EXPECT_FALSE(parse_scenario("fault 1 lightning 3\n", sc, err));
  EXPECT_EQ(err, "line 1: unknown fault kind 'lightning'");
  EXPECT_FALSE(parse_scenario("key 1 1 0 0 0 0 0 0\nkey 0.5 1 0 0 0 0 0 0\n", sc, err));
  EXPECT_EQ(err, "line 2: key times must increase");
  EXPECT_FALSE(parse_scenario("receivers 2 3\n", sc, err));
  EXPECT_EQ(err, "line 1: unexpected '3'");
  EXPECT_FALSE(parse_scenario("bogus\n", sc, err));
}

TEST(Scenario, ButtonLinesParseSortedByTimeAndLeaveKeysAlone) {
  Scenario sc;
  std::string err;
  ASSERT_TRUE(
      parse_scenario("key 0 1 10 -8 5 0 0 0 1\n"
                     "button 2.5 3 1   # hand 1 grab\n"
                     "button 2.5 0 1\n"
                     "button 4 3 0\n"
                     "button 1 15 1\n",
                     sc, err))
      << err;
  ASSERT_EQ(sc.buttons.size(), 4u);
  EXPECT_DOUBLE_EQ(sc.buttons[0].t_s, 1.0);
  EXPECT_EQ(sc.buttons[0].line, 15);
  // Equal times keep file order.
  EXPECT_EQ(sc.buttons[1].line, 3);
  EXPECT_TRUE(sc.buttons[1].pressed);
  EXPECT_EQ(sc.buttons[2].line, 0);
  EXPECT_DOUBLE_EQ(sc.buttons[3].t_s, 4.0);
  EXPECT_FALSE(sc.buttons[3].pressed);
  // The stylus column of key lines is unchanged.
  EXPECT_TRUE(sample(sc, 1, 0.0).button);
  // A file without button lines has none.
  ASSERT_TRUE(parse_scenario("seed 2\n", sc, err));
  EXPECT_TRUE(sc.buttons.empty());
}

TEST(Scenario, MalformedButtonLinesNameTheLine) {
  Scenario sc;
  std::string err;
  EXPECT_FALSE(parse_scenario("seed 1\nbutton 1 3\n", sc, err));
  EXPECT_EQ(err, "line 2: button needs: t line 0|1");
  EXPECT_FALSE(parse_scenario("button x 3 1\n", sc, err));
  EXPECT_EQ(err, "line 1: button needs: t line 0|1");
  EXPECT_FALSE(parse_scenario("\n\nbutton 1 16 1\n", sc, err));
  EXPECT_EQ(err, "line 3: button line must be 0..15");
  EXPECT_FALSE(parse_scenario("button 1 -1 1\n", sc, err));
  EXPECT_EQ(err, "line 1: button line must be 0..15");
  EXPECT_FALSE(parse_scenario("button 1 2 2\n", sc, err));
  EXPECT_EQ(err, "line 1: button level must be 0 or 1");
  EXPECT_FALSE(parse_scenario("button -1 2 1\n", sc, err));
  EXPECT_EQ(err, "line 1: button time must be 0..1000000 s");
  EXPECT_FALSE(parse_scenario("button nan 2 1\n", sc, err));
  EXPECT_FALSE(parse_scenario("button 1 2 1 7\n", sc, err));
  EXPECT_EQ(err, "line 1: unexpected '7'");
}

}  // namespace
}  // namespace twister::sim
