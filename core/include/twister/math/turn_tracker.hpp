// TurnTracker: how far a hand has turned since its start pose, followed continuously
// across tracker samples (docs/unwrap.md). A single pair of poses only gives the
// rotation modulo a full turn, and the minimal screw of docs/math.md §2 folds it into
// [0, pi]; a hand turned by 240 degrees then reads as -120. The tracker instead
// keeps, sample after sample,
//   - the rotation as a unit quaternion whose sign follows the previous sample's
//     (the quaternion path is continuous, so its angle 2 atan2(|v|, w) runs on past
//     pi up to 2 pi instead of folding back), and
//   - an unwrapped signed angle psi about a continuous axis sense n, counted in
//     whole turns too (|psi| > 2 pi after more than a full turn),
// so that the station can build the screw the long way round when the hand has
// turned past a half turn (long_way()), and can hold a stroke once |psi| passes a
// limit. Assumes consecutive samples differ by less than a half turn (a 120 Hz
// tracker and a human hand: a few degrees). Double precision; no allocation.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "twister/math/frame.hpp"

namespace twister::math {

// Below this |v| (sin of the half angle) the axis of a sample is not trusted; the
// previous axis sense is kept (about 2e-9 rad of turn).
inline constexpr double kTurnAxisEpsilon = 1e-9;

class TurnTracker {
 public:
  // Starts from no turn (the start pose itself).
  void reset();

  // Next sample: the rotation from the start pose to `end` (relative_rotation()).
  void follow(const Frame& start, const Frame& end);

  // The unwrapped signed turn psi (radians) about axis() since reset(): continuous
  // in time, any number of turns.
  double turn_rad() const { return turn_rad_; }
  // |psi|: how far the hand has turned, whichever way.
  double turned_rad() const;
  // The axis sense psi is counted about (unit; z until the hand first turns).
  glm::dvec3 axis() const { return axis_; }
  // The tracked rotation (sign continuous from the identity).
  glm::dquat rotation() const { return rotation_; }

  // Whether the minimal screw from `start` to `end` (the last sample's poses) must be
  // taken the long way round (long_way_round()) to turn the way the hand did: the
  // tracked quaternion and the one compute_screw() folds to w >= 0 have opposite
  // signs. Equivalent to "the tracked angle is past a half turn", and exact at the
  // half turn itself. Meaningful while |psi| < 2 pi.
  bool long_way() const;

 private:
  glm::dquat rotation_{1.0, 0.0, 0.0, 0.0};
  glm::dquat minimal_{1.0, 0.0, 0.0, 0.0};  // the last sample folded to w >= 0
  glm::dvec3 axis_{0.0, 0.0, 1.0};
  bool has_axis_ = false;
  double turn_rad_ = 0.0;
};

}  // namespace twister::math
