#include "twister/math/scodef.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <numbers>

#include "math_test_support.hpp"

namespace twister::math {
namespace {

using test::distance;
using test::gen_end_frame;
using test::gen_frame;
using test::gen_real;
using test::gen_unit;

void expect_constraints_met(const ScodefSystem& sys, const Frame* start, const Frame* end,
                            std::size_t hands, double radius) {
  const double eps = kScodefEpsilonFraction * radius;
  for (std::size_t h = 0; h < hands; ++h) {
    for (const auto& [a, b] : {std::pair{start[h].u, end[h].u}, std::pair{start[h].v, end[h].v},
                               std::pair{start[h].w, end[h].w}}) {
      const glm::dvec3 p = start[h].origin + eps * a;
      RC_ASSERT(distance(p + sys.displacement(p), end[h].origin + eps * b) < 1e-9);
    }
  }
}

RC_GTEST_PROP(ScodefTest, OneHandMeetsItsConstraints, ()) {
  const double radius = *gen_real(0.2, 2.0);
  const std::array<Frame, 1> start{*gen_frame(1.0)};
  const std::array<Frame, 1> end{*gen_end_frame(start[0], 1.0)};
  ScodefSystem sys;
  RC_ASSERT(sys.build(start, radius).ok());
  RC_ASSERT(sys.solve(end).ok());
  expect_constraints_met(sys, start.data(), end.data(), 1, radius);
}

RC_GTEST_PROP(ScodefTest, TwoHandsMeetTheirConstraints, ()) {
  const double radius = *gen_real(0.2, 2.0);
  const Frame first = *gen_frame(1.0);
  Frame second = *gen_frame(1.0);
  second.origin = first.origin + radius * *gen_real(0.5, 3.0) * *gen_unit();
  const std::array<Frame, 2> start{first, second};
  const std::array<Frame, 2> end{*gen_end_frame(first, 1.0), *gen_end_frame(second, 1.0)};
  ScodefSystem sys;
  const Status built = sys.build(start, radius);
  RC_PRE(built.ok());  // rare near-singular placements are covered by their own test
  RC_ASSERT(sys.solve(end).ok());
  expect_constraints_met(sys, start.data(), end.data(), 2, radius);
}

TEST(ScodefTest, UnchangedPoseMovesNothing) {
  const std::array<Frame, 1> start{identity_frame()};
  ScodefSystem sys;
  ASSERT_TRUE(sys.build(start, 1.0).ok());
  ASSERT_TRUE(sys.solve(start).ok());
  EXPECT_EQ(sys.displacement(glm::dvec3(0.1, 0.2, 0.0)), glm::dvec3(0.0));
  EXPECT_TRUE(sys.influences(glm::dvec3(0.5, 0.0, 0.0)));
  EXPECT_FALSE(sys.influences(glm::dvec3(1.2, 0.0, 0.0)));
}

// O + eU of hand 1 is the same point as Q + eU' of hand 2: two equal rows.
TEST(ScodefTest, SingularSystemIsReported) {
  const double radius = 1.0;
  const Frame first = identity_frame();
  const Frame second = frame_from_uv(glm::dvec3(0.2, 0.0, 0.0), glm::dvec3(-1.0, 0.0, 0.0),
                                     glm::dvec3(0.0, -1.0, 0.0));
  const std::array<Frame, 2> start{first, second};
  ScodefSystem sys;
  EXPECT_EQ(sys.build(start, radius).code(), StatusCode::failed_precondition);
  EXPECT_FALSE(sys.built());
  EXPECT_EQ(sys.solve(start).code(), StatusCode::failed_precondition);
}

TEST(ScodefTest, BadArguments) {
  ScodefSystem sys;
  const std::array<Frame, 2> same{identity_frame(), identity_frame()};
  EXPECT_EQ(sys.build(same, 1.0).code(), StatusCode::invalid_argument);
  EXPECT_EQ(sys.build(std::span<const Frame>(same.data(), 1), 0.0).code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(sys.build({}, 1.0).code(), StatusCode::invalid_argument);
  ASSERT_TRUE(sys.build(std::span<const Frame>(same.data(), 1), 1.0).ok());
  EXPECT_EQ(sys.solve(same).code(), StatusCode::invalid_argument);
}

}  // namespace
}  // namespace twister::math
