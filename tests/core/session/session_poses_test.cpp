#include "twister/session/session_poses.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "session_harness.hpp"

namespace twister::session {
namespace {

using test_support::z_turn;
constexpr double kPi = std::numbers::pi;

TEST(SessionPoses, HandsStartLostAndTheObjectAtTheWorldOrigin) {
  const SessionPoses p;
  EXPECT_FALSE(p.valid(0));
  EXPECT_FALSE(p.valid(1));
  EXPECT_EQ(p.object().origin, glm::dvec3(0.0));
  EXPECT_EQ(p.object().u, glm::dvec3(1, 0, 0));
}

TEST(SessionPoses, ALostSampleKeepsTheLastValidPose) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(1, true, math::identity_frame({1, 2, 3})).ok());
  EXPECT_TRUE(p.valid(1));
  ASSERT_TRUE(p.set_hand(1, false, math::identity_frame({9, 9, 9})).ok());
  EXPECT_FALSE(p.valid(1));
  EXPECT_EQ(p.hand_in_world(1).origin, glm::dvec3(1, 2, 3));
}

TEST(SessionPoses, ANonOrthonormalPoseIsRefusedAndCountsAsLost) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({1, 0, 0})).ok());
  math::Frame skewed = math::identity_frame({5, 0, 0});
  skewed.u *= 1.1;
  EXPECT_EQ(p.set_hand(0, true, skewed).code(), StatusCode::invalid_argument);
  EXPECT_FALSE(p.valid(0));
  EXPECT_EQ(p.hand_in_world(0).origin, glm::dvec3(1, 0, 0));
}

TEST(SessionPoses, HandOutOfRangeIsRefused) {
  SessionPoses p;
  EXPECT_EQ(p.set_hand(input::kHandCount, true, math::identity_frame()).code(),
            StatusCode::out_of_range);
}

// The journal stores O, U, V only: W must be exactly U x V so replay sees the same frame.
TEST(SessionPoses, WIsRebuiltFromUAndV) {
  SessionPoses p;
  math::Frame f = z_turn({0, 0, 0}, 0.3);
  f.w += glm::dvec3(0, 0, 1e-9);  // orthonormal within tolerance, not bit-exact
  ASSERT_TRUE(p.set_hand(0, true, f).ok());
  EXPECT_EQ(p.hand_in_world(0).w, math::frame_from_uv(f.origin, f.u, f.v).w);
}

TEST(SessionPoses, HandInObjectUndoesTheObjectPose) {
  SessionPoses p;
  p.set_object(z_turn({1, 0, 0}, kPi / 2));  // object turned a quarter about z, at x = 1
  ASSERT_TRUE(p.set_hand(0, true, z_turn({1, 2, 0.5}, kPi / 2)).ok());
  const math::Frame in_object = p.hand_in_object(0);
  EXPECT_NEAR(in_object.origin.x, 2.0, 1e-12);  // world +y is object +x
  EXPECT_NEAR(in_object.origin.y, 0.0, 1e-12);
  EXPECT_NEAR(in_object.origin.z, 0.5, 1e-12);
  EXPECT_NEAR(in_object.u.x, 1.0, 1e-12);  // same turn as the object: aligned
  EXPECT_TRUE(math::is_orthonormal(in_object));
}

TEST(SessionPoses, HandInObjectUsesTheObjectPoseOfTheMoment) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({1, 0, 0})).ok());
  EXPECT_NEAR(p.hand_in_object(0).origin.x, 1.0, 1e-12);
  p.set_object(math::identity_frame({0.25, 0, 0}));
  EXPECT_NEAR(p.hand_in_object(0).origin.x, 0.75, 1e-12);
}

}  // namespace
}  // namespace twister::session
