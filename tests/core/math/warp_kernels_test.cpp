#include "twister/math/warp_kernels.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "math_test_support.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::math {
namespace {

using test::Columns;
using test::gen_end_frame;
using test::gen_frame;
using test::gen_point;
using test::gen_real;
using test::gen_unit;

WarpPlanWithStorage<1024> g_plan;

// The vectorised kernel agrees with the scalar reference, and both with the double
// per-point warp, to 1e-5 of the scene scale (the scene spans [-extent, extent]).
RC_GTEST_PROP(WarpKernelsTest, SimdAgreesWithScalarAndDouble, ()) {
  const double extent = *gen_real(0.5, 4.0);
  const double radius = extent * *gen_real(0.2, 1.5);
  const Frame first = *gen_frame(extent);
  Frame second = *gen_frame(extent);
  second.origin = first.origin + radius * *gen_real(0.05, 2.0) * *gen_unit();
  const bool two = *rc::gen::arbitrary<bool>();
  const WarpMethod method = *rc::gen::element(WarpMethod::twister, WarpMethod::rottran);
  const std::array<Frame, 2> start{first, second};
  const std::array<Frame, 2> end{*gen_end_frame(first, extent), *gen_end_frame(second, extent)};
  const std::size_t hands = two ? 2 : 1;

  const std::size_t n = 512;
  Columns rest(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Half of the points inside the first ball so that most of them are warped.
    const glm::dvec3 p =
        i % 2 == 0 ? first.origin + radius * 0.99 * *gen_point(0.577) : *gen_point(extent);
    rest.x[i] = static_cast<float>(p.x);
    rest.y[i] = static_cast<float>(p.y);
    rest.z[i] = static_cast<float>(p.z);
  }
  RC_ASSERT(g_plan.build(rest.cols(), std::span(start.data(), hands), radius, method).ok());
  RC_ASSERT(g_plan.update(std::span(end.data(), hands)).ok());
  Columns simd(n);
  Columns scalar(n);
  g_plan.set_kernel(KernelKind::simd);
  RC_ASSERT(g_plan.apply(rest.cols(), simd.cols()).ok());
  g_plan.set_kernel(KernelKind::scalar);
  RC_ASSERT(g_plan.apply(rest.cols(), scalar.cols()).ok());
  g_plan.set_kernel(KernelKind::simd);

  // Scene scale: everything the warp touches, rest and warped.
  double scale = extent + radius;
  for (std::size_t h = 0; h < hands; ++h) scale = std::max(scale, glm::length(end[h].origin));
  for (std::uint32_t i : g_plan.indices()) {
    const glm::dvec3 p(rest.x[i], rest.y[i], rest.z[i]);
    const glm::dvec3 exact = g_plan.warp_point(p);
    const glm::dvec3 a(simd.x[i], simd.y[i], simd.z[i]);
    const glm::dvec3 b(scalar.x[i], scalar.y[i], scalar.z[i]);
    RC_ASSERT(glm::length(a - b) <= 1e-5 * scale);
    RC_ASSERT(glm::length(a - exact) <= 1e-5 * scale);
    RC_ASSERT(glm::length(b - exact) <= 1e-5 * scale);
  }
}

TEST(WarpKernelsTest, ZeroWeightLeavesPointsBitExact) {
  KernelHand h;
  h.axis[0] = 0.0;
  h.axis[1] = 1.0;
  h.axis[2] = 0.0;
  h.half_angle = 1.2;
  h.cot_half = 0.4;
  h.chord[0] = 3.0;
  h.shift[2] = 2.0;
  const std::array<float, 4> x{1.5f, -2.0f, 1e6f, 0.1f};
  const std::array<float, 4> w{0.0f, 0.0f, 0.0f, 0.0f};
  std::array<float, 4> ox{}, oy{}, oz{};
  const KernelSpan s{x.data(),  x.data(),  x.data(),  w.data(), w.data(),
                     ox.data(), oy.data(), oz.data(), 4};
  warp_two_simd(h, h, s);
  EXPECT_EQ(0, std::memcmp(ox.data(), x.data(), sizeof(x)));
  EXPECT_EQ(0, std::memcmp(oz.data(), x.data(), sizeof(x)));
  warp_one_scalar(h, s);
  EXPECT_EQ(0, std::memcmp(oy.data(), x.data(), sizeof(x)));
}

TEST(WarpKernelsTest, ReportsIsa) {
  const std::string isa = simd_kernel_isa();
  EXPECT_TRUE(isa == "avx2+fma" || isa == "baseline") << isa;
}

}  // namespace
}  // namespace twister::math
