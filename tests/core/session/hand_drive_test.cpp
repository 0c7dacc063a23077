// HandDrive on its own: the clutch, turns past a half turn and the turn limit, and the
// paper's minimal mode. Label interaction.
#include "twister/session/hand_drive.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "session_harness.hpp"

namespace twister::session {
namespace {

using test_support::z_turn;
constexpr double kPi = std::numbers::pi;

TEST(HandDrive, FollowsTheHandAndTakesTheLongWayPastAHalfTurn) {
  HandDrive d;
  d.start(z_turn({0, 0, 0}, 0));
  for (int k = 1; k <= 24; ++k) {
    EXPECT_EQ(d.follow(z_turn({0.01 * k, 0, 0}, k * 10 * kPi / 180)), TurnLimitChange::none);
    EXPECT_EQ(d.end_pose().origin.x, 0.01 * k);
    EXPECT_EQ(d.long_turn(), k > 18) << k;
  }
  EXPECT_NEAR(d.turned_rad(), 240 * kPi / 180, 1e-9);
}

TEST(HandDrive, OnTheClutchTheEndPoseStaysOnTheStart) {
  HandDrive d;
  d.start(z_turn({0.1, 0, 0}, 0.3));
  (void)d.follow(z_turn({0.2, 0, 0}, 0.5));
  d.set_engaged(false);
  EXPECT_EQ(d.end_pose().origin, d.start_pose().origin);
  EXPECT_EQ(d.follow(z_turn({0.5, 0.5, 0}, 2.0)), TurnLimitChange::none);
  EXPECT_EQ(d.end_pose().origin, d.start_pose().origin);
  EXPECT_FALSE(d.engaged());
  d.set_engaged(true);
  d.start(z_turn({0.5, 0.5, 0}, 2.0));  // re-engaged from where the hand is
  EXPECT_EQ(d.turned_rad(), 0.0);
}

TEST(HandDrive, HoldsPastTheLimitAndFollowsAgainWithinIt) {
  HandDrive d(TurnConfig{TurnTracking::unwrapped, 200 * kPi / 180});
  d.start(z_turn({0, 0, 0}, 0));
  for (int k = 1; k <= 20; ++k) (void)d.follow(z_turn({0, 0, 0}, k * 10 * kPi / 180));
  EXPECT_EQ(d.follow(z_turn({0, 0, 0}, 210 * kPi / 180)), TurnLimitChange::reached);
  EXPECT_TRUE(d.at_limit());
  EXPECT_NEAR(d.limit_rad(), 200 * kPi / 180, 1e-12);
  const math::Frame held = d.end_pose();
  EXPECT_EQ(d.follow(z_turn({0, 0, 0}, 220 * kPi / 180)), TurnLimitChange::none);
  EXPECT_EQ(d.end_pose().u, held.u);
  EXPECT_EQ(d.follow(z_turn({0, 0, 0}, 190 * kPi / 180)), TurnLimitChange::left);
  EXPECT_FALSE(d.at_limit());
  EXPECT_TRUE(d.long_turn());
}

TEST(HandDrive, LimitsAreClampedAndMinimalNeverHolds) {
  EXPECT_NEAR(HandDrive(TurnConfig{TurnTracking::unwrapped, 10.0}).limit_rad(), kMaxTurnLimitRad,
              1e-12);
  EXPECT_NEAR(HandDrive(TurnConfig{TurnTracking::unwrapped, 0.1}).limit_rad(), kMinTurnLimitRad,
              1e-12);
  HandDrive d(TurnConfig{TurnTracking::minimal, kDefaultTurnLimitRad});
  EXPECT_NEAR(d.limit_rad(), kPi, 1e-12);
  d.start(z_turn({0, 0, 0}, 0));
  for (int k = 1; k <= 40; ++k) {
    EXPECT_EQ(d.follow(z_turn({0, 0, 0}, k * 10 * kPi / 180)), TurnLimitChange::none);
    EXPECT_FALSE(d.long_turn());
    EXPECT_FALSE(d.at_limit());
  }
}

}  // namespace
}  // namespace twister::session
