// Turns past a half turn (issue "a session", docs/unwrap.md): the screw the long way
// round, the TurnTracker that decides when to take it, WarpPlan::update_turns and the
// simd kernel's wide-angle loop. Label interaction.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "math_test_support.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/turn_tracker.hpp"
#include "twister/math/warp_kernels.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::math {
namespace {

using test::Columns;
using test::distance;
using test::gen_frame;
using test::gen_point;
using test::gen_real;
using test::gen_unit;
using test::rotated;
constexpr double kPi = std::numbers::pi;

double deg(double d) { return d * kPi / 180.0; }

// The image of the start frame's origin and axis tips under S(1).
void expect_frame_mapped(const Screw& s, const Frame& start, const Frame& end, double tol) {
  EXPECT_LE(distance(screw_at(s, 1.0, start.origin), end.origin), tol);
  EXPECT_LE(distance(screw_at(s, 1.0, start.origin + start.u), end.origin + end.u), tol);
  EXPECT_LE(distance(screw_at(s, 1.0, start.origin + start.v), end.origin + end.v), tol);
  EXPECT_LE(distance(screw_at(s, 1.0, start.origin + start.w), end.origin + end.w), tol);
}

TEST(LongWayRound, IsTheSameMotionTheOtherWayRound) {
  const Frame start = identity_frame({0.1, 0.2, 0.3});
  const Frame end = rotated(start, {0, 0, 1}, deg(-120), {0.3, 0.1, 0.5});
  const Screw minimal = compute_screw(start, end);
  const Screw turned = long_way_round(minimal);
  EXPECT_NEAR(minimal.angle, deg(120), 1e-12);
  EXPECT_NEAR(turned.angle, deg(240), 1e-12);
  EXPECT_EQ(turned.axis, -minimal.axis);
  EXPECT_EQ(turned.slide, -minimal.slide);
  EXPECT_EQ(turned.cot_half, -minimal.cot_half);
  EXPECT_LE(distance(turned.axis_point(), minimal.axis_point()), 1e-12);
  expect_frame_mapped(minimal, start, end, 1e-12);
  expect_frame_mapped(turned, start, end, 1e-12);
  // Half-way a point on the axis of the grab turns by 120 the long way: -120 minimal.
  const glm::dvec3 p = start.origin + glm::dvec3(0.5, 0, 0);
  const glm::dvec3 a = screw_at(turned, 0.5, p) - turned.axis_point();
  const glm::dvec3 b = screw_at(minimal, 0.5, p) - minimal.axis_point();
  EXPECT_NEAR(std::atan2(a.y, a.x) - std::atan2(b.y, b.x), deg(180), 1e-9);
  EXPECT_TRUE(long_way_round(compute_screw(start, start)).pure_translation);
}

TEST(TurnTracker, CountsTurnsPastHalfAndFullTurnsAndBack) {
  const Frame start = identity_frame({0, 0, 0});
  TurnTracker t;
  t.reset();
  for (int k = 1; k <= 144; ++k) {  // 5-degree samples up to 720 degrees
    t.follow(start, rotated(start, {0, 0, 1}, deg(5.0 * k), {0, 0, 0}));
    ASSERT_NEAR(t.turn_rad(), deg(5.0 * k), 1e-9) << k;
    if (5 * k < 360) {
      EXPECT_EQ(t.long_way(), 5 * k > 180) << k;
    }
  }
  for (int k = 143; k >= -40; --k) {  // back through the start to -200
    t.follow(start, rotated(start, {0, 0, 1}, deg(5.0 * k), {0, 0, 0}));
    ASSERT_NEAR(t.turn_rad(), deg(5.0 * k), 1e-9) << k;
  }
  EXPECT_NEAR(t.turned_rad(), deg(200), 1e-9);
  EXPECT_TRUE(t.long_way());
  t.reset();
  EXPECT_EQ(t.turn_rad(), 0.0);
}

// Over random axes that wobble, random speeds and a random start frame: the tracked
// turn moves by no more than the sample-to-sample rotation, its screw (minimal or the
// long way round) always takes the start frame onto the end frame, and the tracked
// angle equals the screw's angle while it is below a full turn.
RC_GTEST_PROP(TurnTracker, ContinuousOverRandomAxesAndSpeeds, ()) {
  const Frame start = *gen_frame(1.0);
  const glm::dvec3 axis0 = *gen_unit();
  const glm::dvec3 wobble = *gen_unit();
  const double speed = *gen_real(deg(0.5), deg(12));  // per sample
  const double sign = *rc::gen::element(-1.0, 1.0);
  const glm::dvec3 drift = 0.01 * *gen_point(1.0);
  TurnTracker t;
  glm::dquat q(1.0, 0.0, 0.0, 0.0);
  double previous = 0.0;
  for (int k = 1; k * speed < deg(340); ++k) {
    const glm::dvec3 axis = glm::normalize(axis0 + 0.2 * std::sin(0.1 * k) * wobble);
    const glm::dquat step = glm::angleAxis(sign * speed, axis);
    q = step * q;
    const Frame end{start.origin + static_cast<double>(k) * drift, q * start.u, q * start.v,
                    q * start.w};
    t.follow(start, end);
    RC_ASSERT(std::fabs(t.turn_rad() - previous) <= speed * (1 + 1e-9) + 1e-12);
    previous = t.turn_rad();
    Screw s = compute_screw(start, end);
    if (t.long_way()) s = long_way_round(s);
    RC_ASSERT(std::fabs(s.angle - t.turned_rad()) <= 1e-9);
    RC_ASSERT(distance(screw_at(s, 1.0, start.origin), end.origin) <= 1e-9);
    RC_ASSERT(distance(screw_at(s, 1.0, start.origin + start.u), end.origin + end.u) <= 1e-9);
    RC_ASSERT(distance(screw_at(s, 1.0, start.origin + start.v), end.origin + end.v) <= 1e-9);
  }
}

// One stroke turning smoothly through 270 degrees on a WarpPlan: the grab point and
// its frame (the warp's Jacobian there) stay on the hand at every sample, and every
// point's warped position moves continuously in time, also across 180 degrees.
TEST(UnwrappedWarpPlan, GrabbedFrameStaysOnTheHandThrough270Degrees) {
  WarpPlanWithStorage<4096> plan;
  const std::size_t n = 2000;
  Columns rest(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 0.002 * static_cast<double>(i);
    rest.x[i] = static_cast<float>(0.4 * std::cos(7 * a));
    rest.y[i] = static_cast<float>(0.4 * std::sin(5 * a));
    rest.z[i] = static_cast<float>(0.2 * std::cos(3 * a));
  }
  const Frame start = identity_frame({0.05, 0.0, 0.0});
  const std::array<Frame, 1> s0{start};
  ASSERT_TRUE(plan.build(rest.cols(), s0, 0.6, WarpMethod::twister).ok());
  TurnTracker t;
  Columns previous(n);
  Columns out(n);
  double max_frame_error = 0.0;
  double max_jump = 0.0;
  const int samples = 270;
  for (int k = 0; k <= samples; ++k) {
    const double angle = deg(270.0 * k / samples);
    const glm::dvec3 origin = start.origin + glm::dvec3(0.0, 0.2, 0.1) * (1.0 * k / samples);
    const Frame end = rotated(start, glm::normalize(glm::dvec3(0.2, 0.1, 1.0)), angle, origin);
    t.follow(start, end);
    const std::array<Frame, 1> e{end};
    ASSERT_TRUE(plan.update_turns(e, t.long_way() ? 1 : 0).ok());
    ASSERT_NEAR(plan.screw(0).angle, angle, 1e-9);
    // The grab point and the warp's Jacobian there (central differences).
    const glm::dvec3 o = plan.warp_point(start.origin);
    max_frame_error = std::max(max_frame_error, distance(o, end.origin));
    const double h = 1e-5;
    for (const auto& [dir, image] :
         {std::pair{start.u, end.u}, std::pair{start.v, end.v}, std::pair{start.w, end.w}}) {
      const glm::dvec3 d =
          (plan.warp_point(start.origin + h * dir) - plan.warp_point(start.origin - h * dir)) /
          (2 * h);
      max_frame_error = std::max(max_frame_error, distance(d, image) * 0.6);  // x radius
    }
    ASSERT_TRUE(plan.apply(rest.cols(), out.cols()).ok());
    if (k > 0) {
      for (std::size_t i = 0; i < n; ++i) {
        max_jump = std::max(max_jump, distance(out.at(i), previous.at(i)));
      }
    }
    previous = out;
  }
  std::printf("270-degree stroke: max frame error %.3g m, max step of a point %.3g m\n",
              max_frame_error, max_jump);
  EXPECT_LE(max_frame_error, 1e-6);
  // 1 degree per sample on points within 0.6 m plus a small drift: a few cm at most;
  // a flip at 180 degrees would move points by up to a diameter.
  EXPECT_LE(max_jump, 0.03);
}

// The simd kernel's wide loop agrees with the scalar reference and the double warp
// for screws the long way round (angles up to 350 degrees), one and two hands.
RC_GTEST_PROP(UnwrappedWarpPlan, SimdAgreesWithScalarPastHalfTurns, ()) {
  static WarpPlanWithStorage<1024> plan;
  const double extent = *gen_real(0.5, 2.0);
  const double radius = extent * *gen_real(0.3, 1.2);
  const Frame first = *gen_frame(extent);
  Frame second = *gen_frame(extent);
  second.origin = first.origin + radius * *gen_real(0.1, 2.0) * *gen_unit();
  const bool two = *rc::gen::arbitrary<bool>();
  const WarpMethod method = *rc::gen::element(WarpMethod::twister, WarpMethod::rottran);
  const std::array<Frame, 2> start{first, second};
  std::array<Frame, 2> end{};
  for (std::size_t h = 0; h < 2; ++h) {
    end[h] = rotated(start[h], *gen_unit(), *gen_real(deg(0), deg(170)),
                     start[h].origin + 0.2 * extent * *gen_point(1.0));
  }
  const auto long_turns = static_cast<std::uint8_t>(*rc::gen::inRange(0, 4));
  const std::size_t hands = two ? 2 : 1;
  const std::size_t n = 256;
  Columns rest(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p = start[i % hands].origin + radius * 0.99 * *gen_point(0.577);
    rest.x[i] = static_cast<float>(p.x);
    rest.y[i] = static_cast<float>(p.y);
    rest.z[i] = static_cast<float>(p.z);
  }
  RC_ASSERT(plan.build(rest.cols(), std::span(start.data(), hands), radius, method).ok());
  RC_ASSERT(plan.update_turns(std::span(end.data(), hands), long_turns).ok());
  Columns simd(n);
  Columns scalar(n);
  plan.set_kernel(KernelKind::simd);
  RC_ASSERT(plan.apply(rest.cols(), simd.cols()).ok());
  plan.set_kernel(KernelKind::scalar);
  RC_ASSERT(plan.apply(rest.cols(), scalar.cols()).ok());
  plan.set_kernel(KernelKind::simd);
  // Past a half turn the screw's helix widens by |cot(a/2)| (docs/unwrap.md).
  double scale = extent + radius;
  for (std::size_t h = 0; h < hands; ++h) {
    scale = std::max(scale, glm::length(end[h].origin)) *
            (1.0 + std::fabs(plan.screw(h).cot_half) * 0.2);
  }
  for (std::uint32_t i : plan.indices()) {
    const glm::dvec3 exact = plan.warp_point({rest.x[i], rest.y[i], rest.z[i]});
    RC_ASSERT(distance(simd.at(i), scalar.at(i)) <= 2e-5 * scale);
    RC_ASSERT(distance(simd.at(i), exact) <= 2e-5 * scale);
  }
}

// Near the largest limit the station allows (350 degrees) the helix of a decayed
// point is wide (|cot(a/2)| = 11.4) but finite; at 359.9 degrees it is 1146 times the
// hand's sideways move, which is why the limit stays well below a full turn.
TEST(UnwrappedWarpPlan, StaysFiniteNearTheLimit) {
  const Frame start = identity_frame({0, 0, 0});
  for (const double a : {330.0, 350.0, 359.9}) {
    const Frame end = rotated(start, {0, 0, 1}, deg(a), {0.05, 0.0, 0.0});
    Screw s = long_way_round(compute_screw(start, end));
    EXPECT_NEAR(s.angle, deg(a), 1e-9);
    double widest = 0.0;
    for (int k = 0; k <= 100; ++k) {
      const glm::dvec3 p = screw_at(s, k / 100.0, {0.1, 0.0, 0.0});
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
      widest = std::max(widest, glm::length(p));
    }
    std::printf("%.1f degrees: |cot(a/2)| %.1f, widest point of the helix %.3f m\n", a,
                std::fabs(s.cot_half), widest);
    EXPECT_LE(widest, 0.1 + 0.05 * std::fabs(s.cot_half));
  }
}

}  // namespace
}  // namespace twister::math
