#include "twister/math/screw.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

#include "math_test_support.hpp"

namespace twister::math {
namespace {

using test::distance;
using test::gen_end_frame;
using test::gen_frame;
using test::gen_point;
using test::gen_real;
using test::rotated;

constexpr double kPi = std::numbers::pi;

RC_GTEST_PROP(ScrewTest, FullScrewAtOneEqualsClosedForm, ()) {
  const Frame start = *gen_frame(2.0);
  const Frame end = *gen_end_frame(start, 2.0);
  const glm::dvec3 p = *gen_point(3.0);
  const Screw s = compute_screw(start, end);
  // The closed form goes through A, which runs off like 1/a for tiny angles: allow
  // its own rounding there (the stable form is what the station evaluates).
  const double slack = s.pure_translation ? 0.0 : 1e-14 * glm::length(s.axis_point());
  RC_ASSERT(distance(screw_at(s, 1.0, p), full_screw_image(s, start, end, p)) < 1e-9 + slack);
}

RC_GTEST_PROP(ScrewTest, FullScrewTakesStartFrameToEndFrame, ()) {
  const Frame start = *gen_frame(2.0);
  const Frame end = *gen_end_frame(start, 2.0);
  const Screw s = compute_screw(start, end);
  RC_ASSERT(distance(screw_at(s, 1.0, start.origin), end.origin) < 1e-9);
  RC_ASSERT(distance(screw_at(s, 1.0, start.origin + start.u), end.origin + end.u) < 1e-9);
  RC_ASSERT(distance(screw_at(s, 1.0, start.origin + start.v), end.origin + end.v) < 1e-9);
  RC_ASSERT(distance(screw_at(s, 1.0, start.origin + start.w), end.origin + end.w) < 1e-9);
}

RC_GTEST_PROP(ScrewTest, ZeroIsIdentity, ()) {
  const Frame start = *gen_frame(2.0);
  const Frame end = *gen_end_frame(start, 2.0);
  const glm::dvec3 p = *gen_point(3.0);
  RC_ASSERT(distance(screw_at(compute_screw(start, end), 0.0, p), p) < 1e-12);
}

RC_GTEST_PROP(ScrewTest, AngleInRangeAndAxisSenseTakesUToUPrime, ()) {
  const Frame start = *gen_frame(2.0);
  const Frame end = *gen_end_frame(start, 2.0);
  const Screw s = compute_screw(start, end);
  RC_ASSERT(s.angle >= 0.0);
  RC_ASSERT(s.angle <= kPi);
  if (!s.pure_translation) {
    const glm::dquat q = glm::angleAxis(s.angle, s.axis);
    RC_ASSERT(distance(q * start.u, end.u) < 1e-9);
    RC_ASSERT(distance(q * start.v, end.v) < 1e-9);
  }
}

// |dS/dt| <= a|P - M| + |X| + |d| (a|X|/(2 tan(a/2)) <= |X|), so a step dt moves the
// point by at most that much: S is continuous in t, also for tiny angles.
RC_GTEST_PROP(ScrewTest, ContinuousInT, ()) {
  const Frame start = *gen_frame(2.0);
  const Frame end = *gen_end_frame(start, 2.0);
  const glm::dvec3 p = *gen_point(3.0);
  const double t = *gen_real(0.0, 1.0);
  const double dt = 1e-6;
  const Screw s = compute_screw(start, end);
  const double speed = s.angle * glm::length(p - s.mid) + glm::length(s.chord) + std::fabs(s.slide);
  RC_ASSERT(distance(screw_at(s, t + dt, p), screw_at(s, t, p)) <= 1.01 * speed * dt + 1e-12);
}

TEST(ScrewTest, PureTranslation) {
  const Frame start = identity_frame(glm::dvec3(1.0, 0.0, 0.0));
  const Frame end = identity_frame(glm::dvec3(1.0, 2.0, 3.0));
  const Screw s = compute_screw(start, end);
  EXPECT_TRUE(s.pure_translation);
  const glm::dvec3 p(5.0, -1.0, 2.0);
  EXPECT_LT(distance(screw_at(s, 0.25, p), p + 0.25 * glm::dvec3(0.0, 2.0, 3.0)), 1e-15);
  EXPECT_LT(distance(full_screw_image(s, start, end, p), p + glm::dvec3(0.0, 2.0, 3.0)), 1e-15);
}

// The literal axis sum U U'xV V' + ... vanishes for this axis with world-aligned frames.
TEST(ScrewTest, AxisPerpendicularToUPlusVPlusW) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0, -1.0, 0.0));
  const Frame start = identity_frame();
  const Frame end = rotated(start, axis, 1.0, glm::dvec3(0.0, 0.0, 0.5));
  const Screw s = compute_screw(start, end);
  EXPECT_NEAR(s.angle, 1.0, 1e-12);
  EXPECT_LT(distance(s.axis, axis), 1e-12);
  EXPECT_NEAR(s.slide, 0.0, 1e-12);
  EXPECT_LT(distance(screw_at(s, 1.0, start.origin + start.w), end.origin + end.w), 1e-12);
}

// The literal axis sum has the wrong sign when k.(U+V+W) < 0.
TEST(ScrewTest, AxisSenseWhenSumWouldFlipIt) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(-1.0, -1.0, -1.0));
  const Frame start = identity_frame();
  const Frame end = rotated(start, axis, 2.0, glm::dvec3(1.0, 0.0, 0.0));
  const Screw s = compute_screw(start, end);
  EXPECT_NEAR(s.angle, 2.0, 1e-12);
  EXPECT_LT(distance(s.axis, axis), 1e-12);
}

TEST(ScrewTest, HalfTurnKeepsPreviousSense) {
  const Frame start = identity_frame();
  const Frame end = rotated(start, glm::dvec3(0.0, 0.0, 1.0), kPi, glm::dvec3(1.0, 1.0, 0.5));
  for (const double sense : {1.0, -1.0}) {
    const glm::dvec3 previous(0.0, 0.0, sense);
    const Screw s = compute_screw(start, end, previous);
    EXPECT_NEAR(s.angle, kPi, 1e-12);
    EXPECT_LT(distance(s.axis, previous), 1e-12);
    EXPECT_NEAR(s.slide, 0.5 * sense, 1e-12);
    // Both senses reach the end pose but move through different halves.
    EXPECT_LT(distance(screw_at(s, 1.0, start.origin + start.u), end.origin + end.u), 1e-12);
    EXPECT_TRUE(std::isfinite(screw_at(s, 0.5, glm::dvec3(3.0, 0.0, 0.0)).x));
  }
}

TEST(ScrewTest, TinyRotationTendsToTranslation) {
  const Frame start = identity_frame(glm::dvec3(0.2, 0.0, 0.0));
  const glm::dvec3 move(0.3, -0.1, 0.2);
  const glm::dvec3 p(1.0, 2.0, -1.0);
  for (const double angle : {1e-6, 1e-9, 1e-11, 1e-13, 0.0}) {
    const Frame end = rotated(start, glm::dvec3(0.0, 1.0, 0.0), angle, start.origin + move);
    const Screw s = compute_screw(start, end);
    const glm::dvec3 q = screw_at(s, 0.5, p);
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
    EXPECT_LT(distance(q, p + 0.5 * move), 10.0 * angle + 1e-12) << angle;
  }
}

TEST(ScrewTest, AxisPointIsFixedByRotationPart) {
  const Frame start = identity_frame(glm::dvec3(1.0, 0.0, 0.0));
  const Frame end = rotated(start, glm::dvec3(0.0, 0.0, 1.0), kPi / 2, glm::dvec3(0.0, 1.0, 0.0));
  const Screw s = compute_screw(start, end);
  // A quarter turn about z through the origin takes (1,0,0) to (0,1,0).
  EXPECT_LT(distance(s.axis_point(), glm::dvec3(0.0)), 1e-12);
  EXPECT_LT(
      distance(screw_at(s, 0.5, start.origin), glm::dvec3(std::sqrt(0.5), std::sqrt(0.5), 0.0)),
      1e-12);
}

TEST(ScrewTest, RottranRotatesAboutGrabPointThenTranslates) {
  const Frame start = identity_frame(glm::dvec3(1.0, 0.0, 0.0));
  const Frame end = rotated(start, glm::dvec3(0.0, 0.0, 1.0), kPi / 2, glm::dvec3(0.0, 1.0, 0.0));
  const Screw s = compute_screw(start, end);
  EXPECT_LT(distance(rottran_at(s, start, end, 1.0, start.origin), end.origin), 1e-12);
  EXPECT_LT(distance(rottran_at(s, start, end, 1.0, start.origin + start.u), end.origin + end.u),
            1e-12);
  // Half way: rotate (2,0,0) by 45 degrees about (1,0,0), then move half of (-1,1,0).
  const glm::dvec3 expected =
      glm::dvec3(1.0 + std::sqrt(0.5), std::sqrt(0.5), 0.0) + glm::dvec3(-0.5, 0.5, 0.0);
  EXPECT_LT(distance(rottran_at(s, start, end, 0.5, glm::dvec3(2.0, 0.0, 0.0)), expected), 1e-12);
}

}  // namespace
}  // namespace twister::math
