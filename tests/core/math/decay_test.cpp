#include "twister/math/decay.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "math_test_support.hpp"

namespace twister::math {
namespace {

using test::gen_point;
using test::gen_real;
using test::gen_unit;

TEST(DecayTest, Values) {
  EXPECT_DOUBLE_EQ(decay(0.0, 2.0), 1.0);
  EXPECT_NEAR(decay(1.0, 2.0), 0.5, 1e-15);
  EXPECT_EQ(decay(2.0, 2.0), 0.0);
  EXPECT_EQ(decay(3.0, 2.0), 0.0);
  EXPECT_LT(decay(1.999999, 2.0), 1e-11);
}

TEST(DecayTest, OneHandWeightIgnoresSquash) {
  const glm::dvec3 o(1.0, 0.0, 0.0);
  EXPECT_NEAR(hand_weight(o, nullptr, 2.0, glm::dvec3(2.0, 0.0, 0.0)), 0.5, 1e-15);
}

TEST(DecayTest, SquashStretchesTowardsOtherHand) {
  const glm::dvec3 o(0.0);
  const glm::dvec3 q(0.5, 0.0, 0.0);
  // s = 0.5, r = 2: the point half way to Q is evaluated at half the radius.
  const glm::dvec3 sq = squash_point(o, q, 2.0, glm::dvec3(0.25, 0.3, 0.0));
  EXPECT_NEAR(sq.x, 1.0, 1e-15);
  EXPECT_NEAR(sq.y, 0.3, 1e-15);
  EXPECT_EQ(hand_weight(o, &q, 2.0, q), 0.0);  // the other grab point has weight 0
  // Behind O and without squash nothing changes.
  EXPECT_EQ(squash_point(o, q, 2.0, glm::dvec3(-0.25, 1.0, 0.0)), glm::dvec3(-0.25, 1.0, 0.0));
  EXPECT_EQ(squash_point(o, glm::dvec3(3.0, 0.0, 0.0), 2.0, glm::dvec3(1.0, 0.0, 0.0)),
            glm::dvec3(1.0, 0.0, 0.0));
}

// docs/math.md §5: on the segment between the hands the two squashed weights sum to one.
RC_GTEST_PROP(DecayTest, PartitionOfUnityOnSegment, ()) {
  const glm::dvec3 o = *gen_point(2.0);
  const double radius = *gen_real(0.1, 3.0);
  const double s = radius * *gen_real(0.01, 0.999);
  const glm::dvec3 q = o + s * *gen_unit();
  const double x = *gen_real(0.0, 1.0);
  const glm::dvec3 p = o + x * (q - o);
  const double sum = hand_weight(o, &q, radius, p) + hand_weight(q, &o, radius, p);
  RC_ASSERT(std::fabs(sum - 1.0) < 1e-9);
}

}  // namespace
}  // namespace twister::math
