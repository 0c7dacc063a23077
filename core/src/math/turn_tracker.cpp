#include "twister/math/turn_tracker.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "twister/math/screw.hpp"

namespace twister::math {

void TurnTracker::reset() { *this = TurnTracker{}; }

void TurnTracker::follow(const Frame& start, const Frame& end) {
  glm::dquat q = relative_rotation(start, end);
  minimal_ = q.w < 0.0 ? -q : q;
  // q and -q are the same rotation; the one nearer the last sample keeps the path
  // on the unit sphere continuous, so its angle runs on past pi.
  if (glm::dot(q, rotation_) < 0.0) q = -q;
  rotation_ = q;
  const glm::dvec3 v(q.x, q.y, q.z);
  const double sin_half = glm::length(v);
  if (sin_half > kTurnAxisEpsilon) {
    glm::dvec3 dir = v / sin_half;
    // Through the identity (and through a full turn) v changes sign: the axis sense
    // stays and psi changes sign (or passes 2 pi) instead.
    if (has_axis_ && glm::dot(dir, axis_) < 0.0) dir = -dir;
    axis_ = dir;
    has_axis_ = true;
  }
  // q = (cos(psi/2), sin(psi/2) n) has period 4 pi in psi: keep the representative
  // nearest the previous sample's psi (samples are less than a half turn apart).
  constexpr double kPeriod = 4.0 * std::numbers::pi;
  double psi = 2.0 * std::atan2(glm::dot(v, axis_), q.w);
  psi += kPeriod * std::round((turn_rad_ - psi) / kPeriod);
  turn_rad_ = psi;
}

double TurnTracker::turned_rad() const { return std::fabs(turn_rad_); }

bool TurnTracker::long_way() const { return glm::dot(rotation_, minimal_) < 0.0; }

}  // namespace twister::math
