// The minimal screw from a start pose to an end pose and its interpolation S(t)
// (docs/math.md §2-§3). Double precision, world frame, scene units; angles in radians.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <optional>

#include "twister/math/frame.hpp"

namespace twister::math {

// Below this angle (radians) the motion is treated as a pure translation: the
// rotation then moves a point at distance 1e3 by less than 1e-9.
inline constexpr double kPureTranslationAngle = 1e-12;
// Within this distance of pi the axis sense is ambiguous (§2) and the previous
// update's sense is kept when one is given.
inline constexpr double kHalfTurnTolerance = 1e-9;

// The screw in the stable form of §2:
//   S(t)(P) = M + Rot(D, t*a)(P - M) + c1(t)*(D x X) + c2(t)*X + t*d*D
// with X = O'' - O, c1 = sin^2(ta/2)*cot(a/2), c2 = sin(ta)*cot(a/2)/2.
// A pure translation has angle 0, cot_half 0, slide 0 and chord = OO'.
struct Screw {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // D, unit; arbitrary for a pure translation
  double angle = 0.0;              // a in [0, pi] (minimal); (pi, 2 pi) the long way round
  double slide = 0.0;              // d = D . OO'
  glm::dvec3 mid{0.0};             // M = (O + O'')/2
  glm::dvec3 chord{0.0};           // X = O'' - O (perpendicular to D); OO' if pure
  double cot_half = 0.0;           // cot(a/2); 0 for a pure translation and at a = pi; < 0 past pi
  bool pure_translation = true;

  // The axis point A = M + (D x X)/(2 tan(a/2)); only meaningful when not pure.
  glm::dvec3 axis_point() const;
};

// Minimal screw taking `start` to `end`. The rotation R = [U'V'W'][UVW]^T gives
// axis and angle through a quaternion (stable near 0 and pi). When the angle is
// within kHalfTurnTolerance of pi and `previous_axis` is given, the axis sense is
// chosen to agree with it (the stroke keeps its sense, §2). Frames must be
// orthonormal (checked by callers); the result is always finite for finite input.
Screw compute_screw(const Frame& start, const Frame& end,
                    std::optional<glm::dvec3> previous_axis = std::nullopt);

// The rotation R = [U'V'W'][UVW]^T from `start` to `end` as a unit quaternion, sign
// as glm::quat_cast gives it (not folded to w >= 0). compute_screw and TurnTracker
// both start from it, so a tracked turn and the screw agree on every bit.
glm::dquat relative_rotation(const Frame& start, const Frame& end);

// The other screw that takes the same start pose to the same end pose: the same
// rotation the long way round (axis -D, angle 2 pi - a, slide -d; the axis point, M
// and X are unchanged, cot(a/2) changes sign). Applied to a minimal screw it gives the
// screw of a turn past a half turn (docs/unwrap.md). A pure translation is returned
// unchanged (a full turn cannot be told from none).
Screw long_way_round(const Screw& minimal);

// S(t)(p) for t in [0, 1] (any t is evaluated; S(0) is the identity, S(1) the full
// screw). Finite and continuous in the angle, including a -> 0 and a = pi.
glm::dvec3 screw_at(const Screw& screw, double t, glm::dvec3 p);

// The closed form P' = (AP.U)U' + (AP.V)V' + (AP.W)W' + dD + A of §2, for tests;
// for a pure translation P + OO'.
glm::dvec3 full_screw_image(const Screw& screw, const Frame& start, const Frame& end, glm::dvec3 p);

// rottran (§6): rotation about the axis through O with direction D by t*a, then
// translation by t*OO'.
glm::dvec3 rottran_at(const Screw& screw, const Frame& start, const Frame& end, double t,
                      glm::dvec3 p);

}  // namespace twister::math
