#include "twister/math/warp_plan.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "math_test_support.hpp"

namespace twister::math {
namespace {

using test::Columns;
using test::distance;
using test::gen_end_frame;
using test::gen_frame;
using test::gen_point;
using test::gen_real;
using test::gen_unit;
using test::rotated;

constexpr double kPi = std::numbers::pi;

// A cloud of points with its columns, for plans in tests.
struct Cloud {
  std::vector<float> x, y, z;
  void add(glm::dvec3 p) {
    x.push_back(static_cast<float>(p.x));
    y.push_back(static_cast<float>(p.y));
    z.push_back(static_cast<float>(p.z));
  }
  ConstVertexColumns rest() const { return {x, y, z}; }
  glm::dvec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

WarpPlanWithStorage<4096> g_plan;  // 48 KiB: static, as the station would do

rc::Gen<WarpMethod> gen_method(bool with_scodef) {
  return with_scodef
             ? rc::gen::element(WarpMethod::twister, WarpMethod::rottran, WarpMethod::scodef)
             : rc::gen::element(WarpMethod::twister, WarpMethod::rottran);
}

// docs/math.md §4: for one hand the grab point and its frame follow the hand exactly.
RC_GTEST_PROP(WarpPlanTest, OneHandGrabPointAndFrameFollowTheHand, ()) {
  const double radius = *gen_real(0.2, 2.0);
  const std::array<Frame, 1> start{*gen_frame(1.0)};
  const std::array<Frame, 1> end{*gen_end_frame(start[0], 1.0)};
  const WarpMethod method = *gen_method(false);
  Cloud cloud;
  cloud.add(start[0].origin);
  RC_ASSERT(g_plan.build(cloud.rest(), start, radius, method).ok());
  RC_ASSERT(g_plan.update(end).ok());
  const glm::dvec3 o = start[0].origin;
  RC_ASSERT(distance(g_plan.warp_point(o), end[0].origin) < 1e-9);
  // The warp's derivative at O maps U, V, W onto U', V', W' (the decay is flat there).
  const double h = 1e-6 * radius;
  for (const auto& [a, b] : {std::pair{start[0].u, end[0].u}, std::pair{start[0].v, end[0].v},
                             std::pair{start[0].w, end[0].w}}) {
    const glm::dvec3 derivative =
        (g_plan.warp_point(o + h * a) - g_plan.warp_point(o - h * a)) / (2 * h);
    RC_ASSERT(distance(derivative, b) < 1e-4);
  }
  // The float kernel puts the grab point there too (float rounding of the scene).
  Columns out(1);
  RC_ASSERT(g_plan.apply(cloud.rest(), out.cols()).ok());
  RC_ASSERT(distance(out.at(0), end[0].origin) < 1e-5 * 4.0);
}

// docs/math.md §5: with |OQ| < r both grab points reach their targets.
RC_GTEST_PROP(WarpPlanTest, TwoHandsInsideEachOthersBallReachTargets, ()) {
  const double radius = *gen_real(0.2, 2.0);
  const Frame first = *gen_frame(1.0);
  Frame second = *gen_frame(1.0);
  second.origin = first.origin + radius * *gen_real(0.01, 0.99) * *gen_unit();
  const std::array<Frame, 2> start{first, second};
  const std::array<Frame, 2> end{*gen_end_frame(first, 1.0), *gen_end_frame(second, 1.0)};
  const WarpMethod method = *gen_method(false);
  Cloud cloud;
  cloud.add(first.origin);
  cloud.add(second.origin);
  RC_ASSERT(g_plan.build(cloud.rest(), start, radius, method).ok());
  RC_ASSERT(g_plan.update(end).ok());
  RC_ASSERT(distance(g_plan.warp_point(first.origin), end[0].origin) < 1e-9);
  RC_ASSERT(distance(g_plan.warp_point(second.origin), end[1].origin) < 1e-9);
  Columns out(2);
  RC_ASSERT(g_plan.apply(cloud.rest(), out.cols()).ok());
  RC_ASSERT(distance(out.at(0), end[0].origin) < 1e-5 * 4.0);
  RC_ASSERT(distance(out.at(1), end[1].origin) < 1e-5 * 4.0);
}

// An unchanged pose is the identity, for every method.
RC_GTEST_PROP(WarpPlanTest, UnchangedPoseIsIdentity, ()) {
  const double radius = *gen_real(0.2, 2.0);
  const Frame first = *gen_frame(1.0);
  Frame second = *gen_frame(1.0);
  second.origin = first.origin + radius * *gen_real(0.3, 3.0) * *gen_unit();
  const bool two = *rc::gen::arbitrary<bool>();
  const std::array<Frame, 2> frames{first, second};
  const std::span<const Frame> start(frames.data(), two ? 2 : 1);
  const WarpMethod method = *gen_method(true);
  Cloud cloud;
  for (int i = 0; i < 64; ++i) cloud.add(*gen_point(2.0));
  const Status built = g_plan.build(cloud.rest(), start, radius, method);
  RC_PRE(built.ok());  // scodef may refuse a singular placement
  RC_ASSERT(g_plan.update(start).ok());
  Columns out(cloud.x.size());
  RC_ASSERT(g_plan.apply(cloud.rest(), out.cols()).ok());
  for (std::uint32_t i : g_plan.indices()) {
    RC_ASSERT(distance(out.at(i), cloud.at(i)) < 1e-12);
    RC_ASSERT(distance(g_plan.warp_point(cloud.at(i)), cloud.at(i)) < 1e-12);
  }
}

TEST(WarpPlanTest, OnlyInfluencedVerticesAreSelectedAndWritten) {
  Cloud cloud;
  for (int i = -20; i <= 20; ++i) cloud.add(glm::dvec3(0.1 * i, 0.0, 0.0));
  const std::array<Frame, 1> start{identity_frame()};
  const std::array<Frame, 1> end{
      rotated(start[0], glm::dvec3(0, 0, 1), 1.0, glm::dvec3(0, 0.5, 0))};
  ASSERT_TRUE(g_plan.build(cloud.rest(), start, 1.0, WarpMethod::twister).ok());
  ASSERT_EQ(g_plan.indices().size(), 19u);  // |x| < 1
  EXPECT_EQ(g_plan.indices().front(), 11u);
  EXPECT_EQ(g_plan.influenced_count(0), 19u);
  EXPECT_EQ(g_plan.influenced_count(1), 0u);
  EXPECT_FLOAT_EQ(g_plan.weights(0)[9], 1.0f);
  EXPECT_TRUE(g_plan.weights(1).empty());
  ASSERT_TRUE(g_plan.update(end).ok());
  Columns out(cloud.x.size(), -99.0f);
  ASSERT_TRUE(g_plan.apply(cloud.rest(), out.cols()).ok());
  for (std::size_t i = 0; i < cloud.x.size(); ++i) {
    const bool influenced = i >= 11 && i < 30;
    EXPECT_EQ(out.x[i] == -99.0f, !influenced) << i;
  }
}

TEST(WarpPlanTest, SparseSelectionMatchesPerPointWarp) {
  Cloud cloud;
  // Interleave far and near points so the selection is not one range (gather path).
  for (int i = 0; i < 1500; ++i) {
    const double a = 0.01 * i;
    cloud.add(glm::dvec3(0.9 * std::cos(a), 0.9 * std::sin(a), 0.001 * i));
    cloud.add(glm::dvec3(50.0 + i, 0.0, 0.0));
  }
  const std::array<Frame, 2> start{identity_frame(glm::dvec3(0.5, 0.0, 0.0)),
                                   identity_frame(glm::dvec3(-0.5, 0.0, 0.0))};
  const std::array<Frame, 2> end{
      rotated(start[0], glm::dvec3(0, 0, 1), 2.0, glm::dvec3(0.6, 0.3, 0.1)),
      rotated(start[1], glm::normalize(glm::dvec3(1, 1, 0)), -2.5, glm::dvec3(-0.4, -0.2, 0.0))};
  for (const KernelKind kind : {KernelKind::simd, KernelKind::scalar}) {
    ASSERT_TRUE(g_plan.build(cloud.rest(), start, 0.8, WarpMethod::twister).ok());
    g_plan.set_kernel(kind);
    ASSERT_TRUE(g_plan.update(end).ok());
    Columns out(cloud.x.size());
    ASSERT_TRUE(g_plan.apply(cloud.rest(), out.cols()).ok());
    ASSERT_GT(g_plan.indices().size(), 300u);
    for (std::uint32_t i : g_plan.indices()) {
      ASSERT_EQ(i % 2, 0u);
      EXPECT_LT(distance(out.at(i), g_plan.warp_point(cloud.at(i))), 1e-5) << i;
    }
  }
  g_plan.set_kernel(KernelKind::simd);
}

TEST(WarpPlanTest, RefusesBadArguments) {
  Cloud cloud;
  cloud.add(glm::dvec3(0.0));
  const Frame f = identity_frame();
  const std::array<Frame, 2> same{f, f};
  const std::array<Frame, 3> three{f, identity_frame(glm::dvec3(1, 0, 0)),
                                   identity_frame(glm::dvec3(2, 0, 0))};
  EXPECT_EQ(g_plan.build(cloud.rest(), same, 1.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  EXPECT_FALSE(g_plan.built());
  EXPECT_EQ(g_plan.build(cloud.rest(), three, 1.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(g_plan.build(cloud.rest(), {}, 1.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  const std::array<Frame, 1> one{f};
  EXPECT_EQ(g_plan.build(cloud.rest(), one, 0.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(g_plan.build(cloud.rest(), one, -1.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  Frame skew = f;
  skew.u = glm::dvec3(1.0, 0.01, 0.0);
  const std::array<Frame, 1> bad{skew};
  EXPECT_EQ(g_plan.build(cloud.rest(), bad, 1.0, WarpMethod::twister).code(),
            StatusCode::invalid_argument);
  Columns out(1);
  EXPECT_EQ(g_plan.apply(cloud.rest(), out.cols()).code(), StatusCode::failed_precondition);
  EXPECT_EQ(g_plan.update(one).code(), StatusCode::failed_precondition);
  ASSERT_TRUE(g_plan.build(cloud.rest(), one, 1.0, WarpMethod::twister).ok());
  EXPECT_EQ(g_plan.update(bad).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g_plan.update(same).code(), StatusCode::invalid_argument);
  Columns wrong(2);
  EXPECT_EQ(g_plan.apply(cloud.rest(), wrong.cols()).code(), StatusCode::invalid_argument);
}

TEST(WarpPlanTest, CapacityTooSmallIsResourceExhausted) {
  WarpPlanWithStorage<8> small;
  Cloud cloud;
  for (int i = 0; i < 9; ++i) cloud.add(glm::dvec3(0.01 * i, 0.0, 0.0));
  const std::array<Frame, 1> start{identity_frame()};
  EXPECT_EQ(small.build(cloud.rest(), start, 1.0, WarpMethod::twister).code(),
            StatusCode::resource_exhausted);
  EXPECT_FALSE(small.built());
  cloud.x.pop_back();
  cloud.y.pop_back();
  cloud.z.pop_back();
  EXPECT_TRUE(small.build(cloud.rest(), start, 1.0, WarpMethod::twister).ok());
  EXPECT_EQ(small.indices().size(), 8u);
}

TEST(WarpPlanTest, RebaseKeepsSelectionAndRestartsFromNewPoses) {
  Cloud cloud;
  for (int i = -10; i <= 10; ++i) cloud.add(glm::dvec3(0.1 * i, 0.05, 0.0));
  const std::array<Frame, 1> start{identity_frame()};
  const std::array<Frame, 1> end{
      rotated(start[0], glm::dvec3(0, 0, 1), 1.5, glm::dvec3(0, 0.5, 0))};
  ASSERT_TRUE(g_plan.build(cloud.rest(), start, 0.55, WarpMethod::twister).ok());
  const std::vector<std::uint32_t> indices(g_plan.indices().begin(), g_plan.indices().end());
  const std::vector<float> weights(g_plan.weights(0).begin(), g_plan.weights(0).end());
  ASSERT_TRUE(g_plan.update(end).ok());
  ASSERT_TRUE(g_plan.rebase(end).ok());
  EXPECT_EQ(std::vector<std::uint32_t>(g_plan.indices().begin(), g_plan.indices().end()), indices);
  EXPECT_EQ(std::vector<float>(g_plan.weights(0).begin(), g_plan.weights(0).end()), weights);
  EXPECT_TRUE(g_plan.screw(0).pure_translation);
  EXPECT_EQ(g_plan.start_frame(0).origin, end[0].origin);
  // A second 150-degree step from the frozen pose reaches 300 degrees in total.
  const std::array<Frame, 1> further{rotated(end[0], glm::dvec3(0, 0, 1), 1.5, end[0].origin)};
  ASSERT_TRUE(g_plan.update(further).ok());
  EXPECT_NEAR(g_plan.screw(0).angle, 1.5, 1e-12);
}

// docs/math.md §2.3: at exactly a half turn the stroke keeps the sense of the previous update.
TEST(WarpPlanTest, HalfTurnKeepsTheStrokeSense) {
  Cloud cloud;
  cloud.add(glm::dvec3(0.0));
  const std::array<Frame, 1> start{identity_frame()};
  for (const double sense : {1.0, -1.0}) {
    const glm::dvec3 axis(0.0, 0.0, sense);
    ASSERT_TRUE(g_plan.build(cloud.rest(), start, 1.0, WarpMethod::twister).ok());
    const std::array<Frame, 1> near{rotated(start[0], axis, kPi - 0.01, glm::dvec3(0.0))};
    ASSERT_TRUE(g_plan.update(near).ok());
    EXPECT_LT(distance(g_plan.screw(0).axis, axis), 1e-12);
    const std::array<Frame, 1> half{rotated(start[0], axis, kPi, glm::dvec3(0.0))};
    ASSERT_TRUE(g_plan.update(half).ok());
    EXPECT_NEAR(g_plan.screw(0).angle, kPi, 1e-12);
    EXPECT_LT(distance(g_plan.screw(0).axis, axis), 1e-12) << sense;
  }
}

// The per-update path (update + apply) allocates nothing, for both kernels and the
// gathered (sparse) layout.
TEST(WarpPlanTest, UpdateAndApplyDoNotAllocate) {
  Cloud cloud;
  for (int i = 0; i < 2000; ++i) cloud.add(glm::dvec3(0.001 * i - 1.0, (i % 3) * 0.4, 0.0));
  Columns out(cloud.x.size());
  const std::array<Frame, 2> start{identity_frame(glm::dvec3(-0.5, 0, 0)),
                                   identity_frame(glm::dvec3(0.5, 0, 0))};
  const std::array<Frame, 2> end{
      rotated(start[0], glm::dvec3(0, 0, 1), 1.0, glm::dvec3(-0.5, 0.3, 0)),
      rotated(start[1], glm::dvec3(0, 0, 1), -1.0, glm::dvec3(0.5, 0.3, 0))};
  for (const WarpMethod method : {WarpMethod::twister, WarpMethod::rottran, WarpMethod::scodef}) {
    for (const KernelKind kind : {KernelKind::simd, KernelKind::scalar}) {
      ASSERT_TRUE(g_plan.build(cloud.rest(), start, 0.5, method).ok());
      g_plan.set_kernel(kind);
      EXPECT_NO_ALLOCATIONS({
        ASSERT_TRUE(g_plan.update(end).ok());
        ASSERT_TRUE(g_plan.apply(cloud.rest(), out.cols()).ok());
        ASSERT_TRUE(g_plan.rebase(end).ok());
      });
    }
  }
  g_plan.set_kernel(KernelKind::simd);
}

}  // namespace
}  // namespace twister::math
