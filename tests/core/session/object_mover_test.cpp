#include "twister/session/object_mover.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <numbers>

#include "session_harness.hpp"

namespace twister::session {
namespace {

using test_support::z_turn;
constexpr double kPi = std::numbers::pi;

void expect_near(const math::Frame& a, const math::Frame& b, double tol = 1e-12) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.origin[i], b.origin[i], tol);
    EXPECT_NEAR(a.u[i], b.u[i], tol);
    EXPECT_NEAR(a.v[i], b.v[i], tol);
  }
}

TEST(ObjectMover, TheObjectFollowsTheHandsMotionRigidly) {
  SessionPoses p;
  p.set_object(math::identity_frame({1, 0, 0}));
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({0, 0, 0})).ok());
  ObjectMover m(p);
  m.begin(0);
  EXPECT_TRUE(m.moving());
  EXPECT_EQ(m.hand(), 0);
  // The hand turns a quarter about z at the world origin and rises by 1: the object,
  // one unit along x from the hand, swings to +y and rises with it.
  ASSERT_TRUE(p.set_hand(0, true, z_turn({0, 0, 1}, kPi / 2)).ok());
  m.follow();
  expect_near(p.object(), z_turn({0, 1, 1}, kPi / 2));
}

TEST(ObjectMover, ALostHandHoldsTheObject) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(1, true, math::identity_frame({0, 0, 0})).ok());
  ObjectMover m(p);
  m.begin(1);
  ASSERT_TRUE(p.set_hand(1, true, math::identity_frame({0, 0.5, 0})).ok());
  m.follow();
  ASSERT_TRUE(p.set_hand(1, false, math::identity_frame({0, 9, 0})).ok());
  m.follow();
  EXPECT_NEAR(p.object().origin.y, 0.5, 1e-12);
}

TEST(ObjectMover, CommitEndsAtTheLastValidPoseAndReportsBeforeAndAfter) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({0, 0, 0})).ok());
  ObjectMover m(p);
  m.begin(0);
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({0, 0, 2})).ok());
  (void)p.set_hand(0, false, {});  // lost before the release: no follow() since
  const Result<ObjectMove> move = m.commit();
  ASSERT_TRUE(move.ok());
  EXPECT_EQ(move->hand, 0);
  EXPECT_EQ(move->before.origin, glm::dvec3(0.0));
  EXPECT_NEAR(move->after.origin.z, 2.0, 1e-12);
  EXPECT_EQ(p.object().origin, move->after.origin);
  EXPECT_FALSE(m.moving());
  EXPECT_EQ(m.commit().status().code(), StatusCode::failed_precondition);
}

TEST(ObjectMover, CancelPutsTheObjectBack) {
  SessionPoses p;
  p.set_object(z_turn({0.3, 0.2, 0.1}, 0.4));
  const math::Frame start = p.object();
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({0, 0, 0})).ok());
  ObjectMover m(p);
  EXPECT_FALSE(m.cancel());  // nothing open
  m.begin(0);
  ASSERT_TRUE(p.set_hand(0, true, z_turn({1, 1, 1}, 1.0)).ok());
  m.follow();
  EXPECT_NE(p.object().origin, start.origin);
  EXPECT_TRUE(m.cancel());
  EXPECT_EQ(p.object().origin, start.origin);
  EXPECT_EQ(p.object().u, start.u);
  EXPECT_FALSE(m.moving());
}

TEST(ObjectMover, FollowWithoutAMoveChangesNothing) {
  SessionPoses p;
  ASSERT_TRUE(p.set_hand(0, true, math::identity_frame({3, 0, 0})).ok());
  ObjectMover m(p);
  m.follow();
  EXPECT_EQ(p.object().origin, glm::dvec3(0.0));
}

// Rounding must not accumulate: each move re-orthonormalises the object frame.
TEST(ObjectMover, ManyMovesKeepTheObjectFrameOrthonormal) {
  SessionPoses p;
  ObjectMover m(p);
  for (int k = 0; k < 1000; ++k) {
    ASSERT_TRUE(p.set_hand(0, true, z_turn({0.1 * (k % 7), 0, 0}, 0.0)).ok());
    m.begin(0);
    const math::Frame f = z_turn({0.1 * (k % 5), 0.2, 0.01 * k}, 0.37 + 0.01 * k);
    const glm::dvec3 v = glm::normalize(f.v + glm::dvec3(0, 0, 0.3));
    ASSERT_TRUE(p.set_hand(0, true, math::frame_from_uv(f.origin, f.u, v)).ok());
    ASSERT_TRUE(m.commit().ok());
  }
  EXPECT_TRUE(math::is_orthonormal(p.object(), 1e-12));
}

}  // namespace
}  // namespace twister::session
