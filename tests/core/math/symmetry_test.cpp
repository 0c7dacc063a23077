// Symmetric warp (docs/math.md §11): equivariance F(gP) = gF(P), exact grab points and
// images, the several-grab-point squash, and the trivial group bit-identical to
// WarpPlan::warp_point. Label symmetry.
#include "twister/math/symmetry.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "math_test_support.hpp"
#include "twister/math/decay.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::math {
namespace {

using test::distance;
using test::gen_end_frame;
using test::gen_frame;
using test::gen_point;
using test::gen_real;

// Worst errors seen, relative to the scene size, printed at the end.
double g_worst_equivariance = 0.0;
double g_worst_grab = 0.0;
// scodef may refuse a stroke whose closest two constraint points (of all images, not
// merged) are this close, relative to the radius (a pivot below 1e-9, §11.8).
constexpr double kScodefRefusedGap = 0.1;

struct GroupSpec {
  int kind = 0;  // 0 mirrors, 1 rotation, 2 rotation with mirror
  int planes = 1;
  int axis = 2;
  int n = 2;
};

SymmetryGroup make_group(const GroupSpec& s) {
  SymmetryGroup g;
  const Status st = s.kind == 0 ? g.set_mirrors(static_cast<std::uint8_t>(s.planes))
                                : g.set_rotation(s.axis, s.n, s.kind == 2);
  RC_ASSERT(st.ok());
  return g;
}

rc::Gen<GroupSpec> gen_group_of_kind(int kind) {
  return rc::gen::apply(
      [kind](int planes, int axis, int n) {
        return GroupSpec{kind, planes, axis, n};
      },
      rc::gen::inRange(1, 8), rc::gen::inRange(0, 3), rc::gen::inRange(2, 13));
}

// Moves a grab point onto (placement 2) or near (placement 1, at a distance in
// [1e-4, 0.3] radius) the fixed set of one of the group's non-identity elements: a
// mirror plane, several planes, the rotation axis.
glm::dvec3 place(const GroupSpec& s, glm::dvec3 o, int placement, double offset, int which) {
  if (placement == 0) return o;
  auto set = [&](int c, double v) { o[c] = placement == 2 ? 0.0 : (o[c] >= 0 ? v : -v); };
  if (s.kind == 0) {
    for (int c = 0; c < 3; ++c) {
      if ((s.planes & (1 << c)) != 0 && ((which >> c) & 1) == 0) set(c, offset);
    }
  } else if (s.kind == 1 || which % 2 == 0) {  // the axis
    set((s.axis + 1) % 3, offset);
    set((s.axis + 2) % 3, offset);
  } else {  // the mirror plane of a and b (c = 0), a plane containing the axis
    set((s.axis + 2) % 3, offset);
  }
  return o;
}

struct Stroke {
  std::vector<Frame> start, end;
  double radius = 1.0;
  WarpMethod method = WarpMethod::twister;
  double scale = 1.0;
};

// Strokes of twister or rottran, or (scodef true) of scodef.
rc::Gen<Stroke> gen_stroke(const GroupSpec& spec, bool scodef = false) {
  return rc::gen::exec([spec, scodef] {
    Stroke s;
    const int hands = *rc::gen::inRange(1, 3);
    s.radius = *gen_real(0.2, 1.5);
    s.method =
        scodef ? WarpMethod::scodef : *rc::gen::element(WarpMethod::twister, WarpMethod::rottran);
    for (int h = 0; h < hands; ++h) {
      Frame f = *gen_frame(1.0);
      // Sometimes axis-aligned: with the grab point on a plane or the axis, constraint
      // points of scodef then lie on it too (a stabiliser of their own, §11.8).
      if (scodef && *rc::gen::inRange(0, 4) == 0) f = identity_frame(f.origin);
      const int placement = *rc::gen::inRange(0, 3);
      const double offset = s.radius * *rc::gen::element(1e-4, 1e-3, 0.01, 0.1, 0.3);
      f.origin = place(spec, f.origin, placement, offset, *rc::gen::inRange(0, 8));
      s.start.push_back(f);
      s.end.push_back(*gen_end_frame(f, 0.5));
    }
    s.scale = s.radius;
    for (std::size_t h = 0; h < s.start.size(); ++h) {
      s.scale = std::max({s.scale, glm::length(s.start[h].origin), glm::length(s.end[h].origin)});
    }
    return s;
  });
}

// Where hand h's grab point image g must go (§11.4), computed from the group alone:
// g.(O + Pi(O' - O)) with O snapped onto the stabiliser's fixed set.
glm::dvec3 expected_target(const SymmetryGroup& group, const Stroke& s, std::size_t h,
                           std::size_t g) {
  const glm::dvec3 o = s.start[h].origin;
  const glm::dvec3 move = s.end[h].origin - o;
  glm::dvec3 snapped(0.0), projected(0.0);
  int stab = 0;
  for (std::size_t e = 0; e < group.order(); ++e) {
    if (distance(group.element(e) * o, o) <= kCoincidentGrabFraction * s.radius) {
      snapped += group.element(e) * o;
      projected += group.element(e) * move;
      ++stab;
    }
  }
  return group.element(g) * ((snapped + projected) / static_cast<double>(stab));
}

// scodef (§11.8): every constraint point O + e U, O + e V, O + e W of every hand (O
// snapped as in §11.4) and every image of one, with its target g.(O' + e U') ...; where
// several coincide, the average of their targets. A hand whose grab point has a
// stabiliser S moves O + x to the average (1/|S|) sum_s s.(O' + R s^T x) of its
// conjugated motions. Computed from the group alone.
struct Constraint {
  glm::dvec3 at, target;
  std::size_t hand = 0;
};

std::vector<Constraint> scodef_constraints(const SymmetryGroup& group, const Stroke& s) {
  const double e = kScodefEpsilonFraction * s.radius;
  std::vector<Constraint> all;
  for (std::size_t h = 0; h < s.start.size(); ++h) {
    const glm::dvec3 o = s.start[h].origin;
    glm::dvec3 snapped(0.0);
    std::vector<glm::dmat3> stab;
    for (std::size_t g = 0; g < group.order(); ++g) {
      if (distance(group.element(g) * o, o) <= kCoincidentGrabFraction * s.radius) {
        snapped += group.element(g) * o;
        stab.push_back(group.element(g));
      }
    }
    snapped /= static_cast<double>(stab.size());
    const Frame& a = s.start[h];
    const Frame& b = s.end[h];
    const glm::dvec3 end = b.origin + (snapped - o);
    // R as a matrix (columns: the images of the basis vectors).
    const glm::dmat3 turn = glm::dmat3(b.u, b.v, b.w) * glm::transpose(glm::dmat3(a.u, a.v, a.w));
    for (const glm::dvec3& from : {a.u, a.v, a.w}) {
      glm::dvec3 target(0.0);
      for (const glm::dmat3& m : stab)
        target += m * (end + turn * (glm::transpose(m) * (e * from)));
      target /= static_cast<double>(stab.size());
      for (std::size_t g = 0; g < group.order(); ++g) {
        const glm::dmat3& m = group.element(g);
        all.push_back({m * (snapped + e * from), m * target, h});
      }
    }
  }
  std::vector<Constraint> merged;
  for (const Constraint& c : all) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (const Constraint& d : all) {
      if (distance(c.at, d.at) <= 3e-9 * s.radius) {
        sum += d.target;
        ++n;
      }
    }
    merged.push_back({c.at, sum / static_cast<double>(n), c.hand});
  }
  return merged;
}

double g_worst_scodef_target = 0.0;
int g_scodef_refused = 0;
int g_scodef_built = 0;
double g_scodef_refused_gap = 0.0;  // the largest closest-pair gap of a refused stroke

void check_scodef_stroke(const SymmetryGroup& group, const Stroke& s, SymmetricWarp& warp,
                         const Status& built) {
  const std::vector<Constraint> cs = scodef_constraints(group, s);
  // The closest two constraint points that are not merged (relative to the radius);
  // constraint points of different hands merged count as 0.
  double gap = 1e9;
  for (const Constraint& a : cs) {
    for (const Constraint& b : cs) {
      const double d = distance(a.at, b.at) / s.radius;
      if (d > 3e-9 || a.hand != b.hand) gap = std::min(gap, d);
    }
  }
  if (built.code() == StatusCode::failed_precondition) {
    ++g_scodef_refused;
    g_scodef_refused_gap = std::max(g_scodef_refused_gap, gap);
    RC_ASSERT(gap <= kScodefRefusedGap);
    return;
  }
  RC_ASSERT(built.ok());
  ++g_scodef_built;
  RC_ASSERT(warp.update(s.end).ok());
  for (const Constraint& c : cs) {
    const double err = distance(warp.warp_point(c.at), c.target) / s.scale;
    g_worst_scodef_target = std::max(g_worst_scodef_target, err);
    RC_ASSERT(err <= 1e-6);
  }
}

void check_stroke(const SymmetryGroup& group, const Stroke& s) {
  SymmetricWarp warp;
  const Status built = warp.build(group, s.start, s.radius, s.method);
  if (s.method == WarpMethod::scodef && built.code() != StatusCode::invalid_argument) {
    check_scodef_stroke(group, s, warp, built);
    if (!built.ok()) return;
  } else if (!built.ok()) {
    // Only two hands whose images coincide are refused.
    RC_ASSERT(built.code() == StatusCode::invalid_argument);
    RC_ASSERT(s.start.size() == 2u);
    bool coincide = false;
    for (std::size_t g = 0; g < group.order(); ++g) {
      coincide |=
          distance(group.element(g) * s.start[0].origin, s.start[1].origin) <= 2e-9 * s.radius;
    }
    RC_ASSERT(coincide);
    return;
  }
  RC_ASSERT(warp.update(s.end).ok());
  // Every grab point and image at its target.
  for (std::size_t h = 0; h < s.start.size() && s.method != WarpMethod::scodef; ++h) {
    for (std::size_t g = 0; g < group.order(); ++g) {
      const glm::dvec3 p = group.element(g) * warp.start_frame(h).origin;
      const double err = distance(warp.warp_point(p), expected_target(group, s, h, g)) / s.scale;
      g_worst_grab = std::max(g_worst_grab, err);
      RC_ASSERT(err <= 1e-6);
    }
  }
  // Equivariance at random points, points near the grab points and on the fixed sets.
  std::vector<glm::dvec3> probes;
  for (int i = 0; i < 6; ++i) probes.push_back(*gen_point(2.0));
  for (std::size_t k = 0; k < warp.grab_point_count(); ++k) {
    probes.push_back(warp.grab_point(k) + *gen_point(0.3 * s.radius));
  }
  for (const glm::dvec3& p : probes) {
    const glm::dvec3 fp = warp.warp_point(p);
    for (std::size_t g = 1; g < group.order(); ++g) {
      const glm::dmat3& m = group.element(g);
      const double err = distance(warp.warp_point(m * p), m * fp) / s.scale;
      g_worst_equivariance = std::max(g_worst_equivariance, err);
      RC_ASSERT(err <= 1e-6);
    }
  }
}

TEST(SymmetryGroup, ElementsFormTheGroup) {
  SymmetryGroup g;
  EXPECT_TRUE(g.trivial());
  EXPECT_EQ(g.set_mirrors(0).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g.set_mirrors(8).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g.set_rotation(3, 4, false).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g.set_rotation(2, 1, false).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g.set_rotation(2, 13, true).code(), StatusCode::invalid_argument);
  EXPECT_TRUE(g.trivial());
  struct Case {
    int kind, planes, axis, n;
    std::size_t order;
  };
  for (const Case c : {Case{0, 1, 0, 0, 2}, Case{0, 3, 0, 0, 4}, Case{0, 7, 0, 0, 8},
                       Case{1, 0, 2, 6, 6}, Case{2, 0, 0, 12, 24}, Case{2, 0, 1, 2, 4}}) {
    ASSERT_TRUE((c.kind == 0 ? g.set_mirrors(static_cast<std::uint8_t>(c.planes))
                             : g.set_rotation(c.axis, c.n, c.kind == 2))
                    .ok());
    ASSERT_EQ(g.order(), c.order);
    EXPECT_EQ(g.element(0), glm::dmat3(1.0));
    // Orthogonal, and closed under products (each product is an element).
    for (std::size_t i = 0; i < g.order(); ++i) {
      const glm::dmat3& a = g.element(i);
      const glm::dmat3 ata = glm::transpose(a) * a;
      for (int r = 0; r < 3; ++r) {
        for (int col = 0; col < 3; ++col) EXPECT_NEAR(ata[col][r], r == col ? 1.0 : 0.0, 1e-15);
      }
      for (std::size_t j = 0; j < g.order(); ++j) {
        const glm::dmat3 ab = a * g.element(j);
        double best = 1e9;
        for (std::size_t k = 0; k < g.order(); ++k) {
          double d = 0.0;
          for (int col = 0; col < 3; ++col) d += glm::length(ab[col] - g.element(k)[col]);
          best = std::min(best, d);
        }
        EXPECT_LE(best, 1e-14);
      }
    }
  }
}

RC_GTEST_PROP(SymmetricWarp, MirrorsAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(0);
  check_stroke(make_group(spec), *gen_stroke(spec));
}

RC_GTEST_PROP(SymmetricWarp, RotationsAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(1);
  check_stroke(make_group(spec), *gen_stroke(spec));
}

RC_GTEST_PROP(SymmetricWarp, RotationsWithMirrorAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(2);
  check_stroke(make_group(spec), *gen_stroke(spec));
}

RC_GTEST_PROP(SymmetricScodef, MirrorsAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(0);
  check_stroke(make_group(spec), *gen_stroke(spec, true));
}

RC_GTEST_PROP(SymmetricScodef, RotationsAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(1);
  check_stroke(make_group(spec), *gen_stroke(spec, true));
}

RC_GTEST_PROP(SymmetricScodef, RotationsWithMirrorAreSymmetricAndExact, ()) {
  const GroupSpec spec = *gen_group_of_kind(2);
  check_stroke(make_group(spec), *gen_stroke(spec, true));
}

// The trivial group: every bit as WarpPlan::warp_point (both methods, 1 and 2 hands,
// apart, overlapping and squashed balls).
RC_GTEST_PROP(SymmetricWarp, TrivialGroupIsBitIdenticalToWarpPlan, ()) {
  const Stroke s = *gen_stroke(GroupSpec{});
  WarpPlanWithStorage<4> plan;
  const ConstVertexColumns none{};
  const Status plan_built = plan.build(none, s.start, s.radius, s.method);
  SymmetricWarp warp;
  const Status built = warp.build(SymmetryGroup{}, s.start, s.radius, s.method);
  RC_ASSERT(plan_built.code() == built.code());
  if (!built.ok()) return;
  RC_ASSERT(plan.update(s.end).ok());
  RC_ASSERT(warp.update(s.end).ok());
  for (int i = 0; i < 20; ++i) {
    const glm::dvec3 p = i < 10 ? *gen_point(2.0)
                                : s.start[static_cast<std::size_t>(i) % s.start.size()].origin +
                                      *gen_point(s.radius);
    const glm::dvec3 a = plan.warp_point(p);
    const glm::dvec3 b = warp.warp_point(p);
    RC_ASSERT(std::memcmp(&a, &b, sizeof a) == 0);
  }
}

// scodef under the trivial group is the plain ScodefSystem (another factorisation of
// the same system: equal to rounding).
RC_GTEST_PROP(SymmetricScodef, TrivialGroupIsPlainScodef, ()) {
  const Stroke s = *gen_stroke(GroupSpec{}, true);
  WarpPlanWithStorage<4> plan;
  const Status plan_built = plan.build(ConstVertexColumns{}, s.start, s.radius, s.method);
  SymmetricWarp warp;
  const Status built = warp.build(SymmetryGroup{}, s.start, s.radius, s.method);
  RC_PRE(plan_built.ok() && built.ok());
  RC_ASSERT(plan.update(s.end).ok());
  RC_ASSERT(warp.update(s.end).ok());
  for (int i = 0; i < 20; ++i) {
    const glm::dvec3 p = i < 10 ? *gen_point(2.0)
                                : s.start[static_cast<std::size_t>(i) % s.start.size()].origin +
                                      *gen_point(s.radius);
    RC_ASSERT(distance(plan.warp_point(p), warp.warp_point(p)) <= 1e-9 * s.scale);
  }
}

// A clutch step of a symmetric scodef stroke (WarpPlan::rebase): the system is built
// anew at the new start poses; a hand on a plane stays on it. The rebased warp is
// symmetric and the new constraint points reach their new targets.
TEST(SymmetricScodef, RebaseBuildsTheSystemAtTheNewPoses) {
  SymmetryGroup g;
  ASSERT_TRUE(g.set_mirrors(kMirrorX | kMirrorY).ok());
  const std::array<Frame, 2> start{
      identity_frame({0.0, 0.3, 0.1}),
      test::rotated(identity_frame({0.4, -0.2, 0.0}), {0.6, 0.8, 0}, 0.3, {0.4, -0.2, 0.0})};
  const std::array<Frame, 2> mid{test::rotated(start[0], {0, 0, 1}, 0.2, {0.05, 0.35, 0.15}),
                                 test::rotated(start[1], {0, 1, 0}, 0.4, {0.45, -0.25, 0.05})};
  const std::array<Frame, 2> end{test::rotated(mid[0], {0, 1, 0}, 0.3, {0.1, 0.4, 0.1}),
                                 test::rotated(mid[1], {1, 0, 0}, 0.2, {0.5, -0.2, 0.1})};
  SymmetricWarp warp;
  ASSERT_TRUE(warp.build(g, start, 0.5, WarpMethod::scodef).ok());
  ASSERT_TRUE(warp.update(mid).ok());
  ASSERT_TRUE(warp.rebase(mid).ok());
  ASSERT_TRUE(warp.update(end).ok());
  EXPECT_EQ(warp.stabiliser_size(0), 2u);  // still on the plane x = 0
  EXPECT_EQ(warp.start_frame(0).origin.x, 0.0);
  const double e = kScodefEpsilonFraction * 0.5;
  for (const auto& [a, b] : {std::pair{mid[1].u, end[1].u}, std::pair{mid[1].v, end[1].v},
                             std::pair{mid[1].w, end[1].w}}) {
    for (std::size_t k = 0; k < g.order(); ++k) {
      const glm::dmat3& m = g.element(k);
      EXPECT_LE(distance(warp.warp_point(m * (mid[1].origin + e * a)), m * (end[1].origin + e * b)),
                1e-9);
    }
  }
  for (int i = 0; i < 50; ++i) {
    const glm::dvec3 p(0.02 * i - 0.5, 0.3 - 0.011 * i, 0.1 + 0.003 * i);
    for (std::size_t k = 1; k < g.order(); ++k) {
      const glm::dmat3& m = g.element(k);
      EXPECT_LE(distance(warp.warp_point(m * p), m * warp.warp_point(p)), 1e-12);
    }
  }
}

// §11.3: at every grab point exactly one weight is 1 and the others 0; with one other
// grab point in the ball the weight is the paper's squash (§5).
TEST(SymmetricWarp, WeightsInterpolateWithSeveralGrabPointsInABall) {
  SymmetryGroup g;
  ASSERT_TRUE(g.set_rotation(2, 6, true).ok());
  // Hand 1 near the axis (its 12 images within one ball), hand 2 near hand 1.
  const Frame a = identity_frame({0.1, 0.03, 0.2});
  const Frame b = identity_frame({0.25, -0.05, 0.3});
  const std::array<Frame, 2> start{a, b};
  SymmetricWarp warp;
  ASSERT_TRUE(warp.build(g, start, 0.5, WarpMethod::twister).ok());
  EXPECT_EQ(warp.grab_point_count(), 24u);
  for (std::size_t k = 0; k < warp.grab_point_count(); ++k) {
    for (std::size_t j = 0; j < warp.grab_point_count(); ++j) {
      const double w = warp.weight(k, warp.grab_point(j));
      if (j == k) {
        EXPECT_EQ(w, 1.0);
      } else {
        EXPECT_LE(w, 1e-20) << k << " at " << j;
      }
    }
  }
  // No bump: on the segment between two grab points two weights sum to at most 1.
  for (std::size_t j = 1; j < warp.grab_point_count(); ++j) {
    for (int i = 0; i <= 20; ++i) {
      const glm::dvec3 p = glm::mix(warp.grab_point(0), warp.grab_point(j), i / 20.0);
      EXPECT_LE(warp.weight(0, p) + warp.weight(j, p), 1.0 + 1e-12);
    }
  }
  // Two hands, no symmetry: the weight is hand_weight (the paper's squash).
  SymmetricWarp plain;
  ASSERT_TRUE(plain.build(SymmetryGroup{}, start, 0.5, WarpMethod::twister).ok());
  const glm::dvec3 p(0.2, 0.0, 0.25);
  EXPECT_EQ(plain.weight(0, p), hand_weight(a.origin, &b.origin, 0.5, p));
  EXPECT_EQ(plain.weight(1, p), hand_weight(b.origin, &a.origin, 0.5, p));
}

// §11.4: a grab point on a mirror plane moves by the projection of its translation,
// and counts once; a hand on an image of the other is refused.
TEST(SymmetricWarp, GrabPointOnAPlaneMovesByItsSymmetricPart) {
  SymmetryGroup g;
  ASSERT_TRUE(g.set_mirrors(kMirrorX).ok());
  const Frame start = identity_frame({0.0, 0.2, 0.1});
  const Frame end = test::rotated(start, {0, 0, 1}, 0.4, {0.3, 0.25, 0.1});
  SymmetricWarp warp;
  ASSERT_TRUE(warp.build(g, std::span(&start, 1), 0.5, WarpMethod::twister).ok());
  ASSERT_TRUE(warp.update(std::span(&end, 1)).ok());
  EXPECT_EQ(warp.grab_point_count(), 1u);
  EXPECT_EQ(warp.stabiliser_size(0), 2u);
  EXPECT_LE(distance(warp.warp_point(start.origin), {0.0, 0.25, 0.1}), 1e-15);
  // The mirror image of hand 2 is hand 1: refused.
  const std::array<Frame, 2> mirrored{identity_frame({0.3, 0.1, 0.0}),
                                      identity_frame({-0.3, 0.1, 0.0})};
  EXPECT_EQ(warp.build(g, mirrored, 0.5, WarpMethod::twister).code(), StatusCode::invalid_argument);
  EXPECT_FALSE(warp.built());
  EXPECT_EQ(warp.build(g, mirrored, 0.5, WarpMethod::scodef).code(), StatusCode::invalid_argument);
}

TEST(SymmetricWarp, NoHeapAllocation) {
  SymmetryGroup g;
  ASSERT_TRUE(g.set_rotation(1, 12, true).ok());
  const std::array<Frame, 2> start{identity_frame({0.1, 0.0, 0.2}),
                                   identity_frame({0.3, 0.1, -0.2})};
  const std::array<Frame, 2> end{test::rotated(start[0], {0, 1, 0}, 1.0, {0.2, 0.1, 0.2}),
                                 test::rotated(start[1], {1, 0, 0}, 0.5, {0.3, 0.2, -0.2})};
  static SymmetricWarp warp;
  glm::dvec3 out(0.0);
  EXPECT_NO_ALLOCATIONS({
    (void)warp.build(g, start, 0.4, WarpMethod::twister);
    (void)warp.update(end);
    out = warp.warp_point({0.2, 0.1, 0.1});
  });
  EXPECT_TRUE(std::isfinite(out.x));
  // scodef (§11.8): its system, its solve, a clutch step.
  EXPECT_NO_ALLOCATIONS({
    EXPECT_TRUE(warp.build(g, start, 0.4, WarpMethod::scodef).ok());
    EXPECT_TRUE(warp.update(end).ok());
    out = warp.warp_point({0.2, 0.1, 0.1});
    EXPECT_TRUE(warp.rebase(end).ok());
  });
  EXPECT_TRUE(std::isfinite(out.x));
}

// The float path (docs/math.md §11.7): WarpPlan::apply under a group with the simd
// kernel and PlanSymmetry's sorted order and weights.
double g_worst_float_vs_double = 0.0;
double g_worst_float_symmetry = 0.0;
double g_worst_float_grab = 0.0;

struct FloatScene {
  std::vector<float> x, y, z, ox, oy, oz, sx, sy, sz, w1, w2, weights;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint64_t> balls;
  PlanSymmetry symmetry;
  std::unique_ptr<WarpPlan> plan;
  std::size_t base_points = 0;     // points 0 .. base_points-1 have their images at orbit
  std::vector<std::size_t> orbit;  // orbit[i * order + g]: the vertex fl(g p_i)

  void add(glm::dvec3 p) {
    x.push_back(static_cast<float>(p.x));
    y.push_back(static_cast<float>(p.y));
    z.push_back(static_cast<float>(p.z));
  }
  glm::dvec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
  glm::dvec3 out(std::size_t i) const { return {ox[i], oy[i], oz[i]}; }
  // Allocates the plan's storage for the current points (with_weights: the kept
  // weights; else recomputed per apply).
  void make_plan(bool with_weights) {
    const std::size_t n = x.size();
    ox = x;
    oy = y;
    oz = z;
    for (auto* v : {&sx, &sy, &sz, &w1, &w2}) v->assign(n, 0.0f);
    indices.assign(n, 0);
    balls.assign(SymmetricFloat::words_for(n), 0);
    weights.assign(with_weights ? SymmetricFloat::weights_for(n) : 0, 0.0f);
    symmetry.start = VertexColumns{sx, sy, sz};
    symmetry.balls = balls;
    symmetry.weights = weights;
    plan = std::make_unique<WarpPlan>(WarpPlanStorage{indices, w1, w2, &symmetry});
  }
};

// Random points, points near every grab point and image, the grab points and images
// themselves, each with its images under the group (rounded to float).
void fill_scene(FloatScene& sc, const SymmetryGroup& group, const SymmetricWarp& warp) {
  std::vector<glm::dvec3> base;
  for (int i = 0; i < 24; ++i) base.push_back(*gen_point(2.0));
  for (std::size_t k = 0; k < warp.grab_point_count(); ++k) {
    base.push_back(warp.grab_point(k));
    for (int i = 0; i < 6; ++i) base.push_back(warp.grab_point(k) + *gen_point(warp.radius()));
  }
  const std::size_t order = group.order();
  sc.base_points = base.size();
  for (const glm::dvec3& p : base) sc.add(p);
  sc.orbit.assign(base.size() * order, 0);
  for (std::size_t i = 0; i < base.size(); ++i) {
    sc.orbit[i * order] = i;
    for (std::size_t g = 1; g < order; ++g) {
      sc.orbit[i * order + g] = sc.x.size();
      sc.add(group.element(g) * sc.at(i));
    }
  }
}

void check_float_stroke(const SymmetryGroup& group, Stroke s, bool with_weights) {
  // Grab points that are float points (a vertex can sit exactly on one).
  // (Through volatile floats: GCC 12 at -O3 left some components unrounded, the
  // double -> float -> double round trip folded away.)
  std::vector<Frame> rounded;
  for (const Frame& f : s.start) {
    volatile float fx = static_cast<float>(f.origin.x);
    volatile float fy = static_cast<float>(f.origin.y);
    volatile float fz = static_cast<float>(f.origin.z);
    const glm::dvec3 o(fx, fy, fz);
    rounded.push_back(Frame{o, f.u, f.v, f.w});
  }
  s.start = rounded;
  SymmetricWarp reference;
  if (!reference.build(group, s.start, s.radius, s.method).ok()) return;  // refused: above
  RC_ASSERT(reference.update(s.end).ok());
  FloatScene sc;
  fill_scene(sc, group, reference);
  sc.make_plan(with_weights);
  const ConstVertexColumns rest{sc.x, sc.y, sc.z};
  RC_ASSERT(sc.plan->build(rest, s.start, s.radius, s.method, group).ok());
  RC_ASSERT(sc.symmetry.fast.ready());
  twister::test::AllocationCounter allocations;
  const bool updated = sc.plan->update(s.end).ok();
  const std::size_t after_update = allocations.count();
  const bool applied = sc.plan->apply(rest, VertexColumns{sc.ox, sc.oy, sc.oz}).ok();
  const std::size_t after_apply = allocations.count();
  RC_ASSERT(updated);
  RC_ASSERT(applied);
  RC_ASSERT(after_update == 0u);
  RC_ASSERT(after_apply == 0u);
  // Equal to the double warp at the same (float) points.
  const SymmetricWarp& warp = *sc.plan->symmetric_warp();
  std::vector<glm::dvec3> exact(sc.x.size());
  for (std::size_t i = 0; i < sc.x.size(); ++i) {
    exact[i] = warp.warp_point(sc.at(i));
    const double err = distance(sc.out(i), exact[i]) / s.scale;
    g_worst_float_vs_double = std::max(g_worst_float_vs_double, err);
    RC_ASSERT(err <= 1e-5);
  }
  // The refiner's float batch (warp_points_float) within its bound of the double warp.
  double extent = 0.0;
  for (std::size_t i = 0; i < sc.x.size(); ++i) {
    extent = std::max(
        {extent, std::abs(double{sc.x[i]}), std::abs(double{sc.y[i]}), std::abs(double{sc.z[i]})});
  }
  const double bound = sc.plan->float_error_bound(extent);
  for (std::size_t base = 0; base < sc.x.size(); base += WarpPlan::kFloatChunk) {
    const std::size_t n = std::min(WarpPlan::kFloatChunk, sc.x.size() - base);
    float bx[WarpPlan::kFloatChunk], by[WarpPlan::kFloatChunk], bz[WarpPlan::kFloatChunk];
    RC_ASSERT(sc.plan->warp_points_float(&sc.x[base], &sc.y[base], &sc.z[base], bx, by, bz, n));
    for (std::size_t i = 0; i < n; ++i) {
      RC_ASSERT(distance(glm::dvec3(bx[i], by[i], bz[i]), exact[base + i]) <= bound);
    }
  }
  // Symmetric: F(fl(g p)) against g F(p), beyond what the double warp itself gives for
  // the same float inputs (fl(g p) is g p exactly for mirrors, to ~1e-7 for rotations).
  const std::size_t order = group.order();
  for (std::size_t i = 0; i < sc.base_points; ++i) {
    for (std::size_t g = 1; g < order; ++g) {
      const glm::dmat3& m = group.element(g);
      const std::size_t j = sc.orbit[i * order + g];
      const double input = distance(exact[j], m * exact[i]) / s.scale;
      const double err = distance(sc.out(j), m * sc.out(i)) / s.scale;
      g_worst_float_symmetry = std::max(g_worst_float_symmetry, err - input);
      RC_ASSERT(err <= 1e-5 + input);
    }
  }
  // Every grab point and image that is a vertex reaches its end pose as the double warp
  // does (to 1e-6 of the scene size beyond the double warp at that float point).
  for (std::size_t i = 0; i < sc.base_points; ++i) {
    for (std::size_t h = 0; h < s.start.size(); ++h) {
      if (distance(sc.at(i), s.start[h].origin) != 0.0) continue;
      for (std::size_t g = 0; g < order; ++g) {
        const std::size_t j = sc.orbit[i * order + g];
        const glm::dvec3 target = expected_target(group, s, h, g);
        const double err = distance(sc.out(j), target) / s.scale;
        const double input = distance(exact[j], target) / s.scale;
        g_worst_float_grab = std::max(g_worst_float_grab, err - input);
        RC_ASSERT(err <= 1e-6 + input);
      }
    }
  }
}

// A clutch chain: after a rebase the points move from the rest columns given to apply
// (the previous step's result), with the weights of their chain start: the float path
// against the plan's double path (the scalar kernel) on the same columns.
void check_float_chain(const SymmetryGroup& group, const Stroke& s) {
  SymmetricWarp reference;
  if (!reference.build(group, s.start, s.radius, s.method).ok()) return;
  FloatScene sc;
  fill_scene(sc, group, reference);
  sc.make_plan(*rc::gen::arbitrary<bool>());
  RC_ASSERT(sc.plan->build(ConstVertexColumns{sc.x, sc.y, sc.z}, s.start, s.radius, s.method, group)
                .ok());
  RC_ASSERT(sc.plan->update(s.end).ok());
  RC_ASSERT(sc.plan->apply(ConstVertexColumns{sc.x, sc.y, sc.z}, VertexColumns{sc.ox, sc.oy, sc.oz})
                .ok());
  // Step 2: from where step 1 left the points, the hands turn further.
  const std::vector<float> qx = sc.ox, qy = sc.oy, qz = sc.oz;
  RC_ASSERT(sc.plan->rebase(s.end).ok());
  std::vector<Frame> further;
  for (const Frame& f : s.end) further.push_back(*gen_end_frame(f, 0.3));
  RC_ASSERT(sc.plan->update(further).ok());
  const ConstVertexColumns q{qx, qy, qz};
  std::vector<float> fx = qx, fy = qy, fz = qz, dx = qx, dy = qy, dz = qz;
  RC_ASSERT(sc.plan->apply(q, VertexColumns{fx, fy, fz}).ok());
  sc.plan->set_kernel(KernelKind::scalar);
  RC_ASSERT(sc.plan->apply(q, VertexColumns{dx, dy, dz}).ok());
  for (std::size_t i = 0; i < fx.size(); ++i) {
    const double err = distance(glm::dvec3(fx[i], fy[i], fz[i]), glm::dvec3(dx[i], dy[i], dz[i]));
    RC_ASSERT(err <= 1e-5 * (s.scale + 2.0));
  }
}

RC_GTEST_PROP(SymmetricFloat, ClutchChainsMatchTheDoublePath, ()) {
  const GroupSpec spec = *gen_group_of_kind(*rc::gen::inRange(0, 3));
  check_float_chain(make_group(spec), *gen_stroke(spec));
}

RC_GTEST_PROP(SymmetricFloat, MirrorsMatchTheDoubleWarpAndAreSymmetric, ()) {
  const GroupSpec spec = *gen_group_of_kind(0);
  check_float_stroke(make_group(spec), *gen_stroke(spec), *rc::gen::arbitrary<bool>());
}

RC_GTEST_PROP(SymmetricFloat, RotationsMatchTheDoubleWarpAndAreSymmetric, ()) {
  const GroupSpec spec = *gen_group_of_kind(1);
  check_float_stroke(make_group(spec), *gen_stroke(spec), *rc::gen::arbitrary<bool>());
}

RC_GTEST_PROP(SymmetricFloat, RotationsWithMirrorMatchTheDoubleWarpAndAreSymmetric, ()) {
  const GroupSpec spec = *gen_group_of_kind(2);
  check_float_stroke(make_group(spec), *gen_stroke(spec), *rc::gen::arbitrary<bool>());
}

TEST(SymmetryReport, WorstErrors) {
  std::printf("symmetry: worst |F(gp) - gF(p)| %.3g, worst grab point error %.3g (x scene size)\n",
              g_worst_equivariance, g_worst_grab);
  std::printf(
      "symmetry float path: worst |float - double| %.3g, worst asymmetry beyond the input's "
      "%.3g, worst grab point beyond double %.3g (x scene size)\n",
      g_worst_float_vs_double, g_worst_float_symmetry, g_worst_float_grab);
  std::printf(
      "symmetric scodef: %d strokes built, %d refused (singular; largest closest-pair gap "
      "refused %.3g r), worst constraint point error %.3g (x scene size)\n",
      g_scodef_built, g_scodef_refused, g_scodef_refused_gap, g_worst_scodef_target);
}

}  // namespace
}  // namespace twister::math
