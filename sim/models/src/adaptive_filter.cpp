// The simulator's adaptive filter (see adaptive_filter.hpp).
#include "twister/sim/adaptive_filter.hpp"

#include <algorithm>
#include <cmath>

namespace twister::sim {

bool AdaptiveFilter::adapt(double relative_step, const FilterParams& p) {
  if (!p.enabled() || !primed_) {
    primed_ = p.enabled();
    alpha_ = p.enabled() ? p.fhigh : 1.0;
    return false;
  }
  // The pole moves between FLOW (still input) and FHIGH (a full step or more).
  const double target = p.flow + (p.fhigh - p.flow) * std::min(1.0, relative_step);
  double a = p.f * target + (1.0 - p.f) * alpha_;
  if (a < alpha_) a = std::max(a, alpha_ * p.factor);  // FACTOR limits the narrowing
  alpha_ = std::clamp(a, p.flow, p.fhigh);
  return true;
}

glm::dvec3 AdaptiveFilter::position(const glm::dvec3& in, const FilterParams& p) {
  const double step = primed_ ? glm::length(in - position_) / kFullStepInches : 0.0;
  if (!adapt(step, p)) {
    position_ = in;
    return in;
  }
  position_ = alpha_ * in + (1.0 - alpha_) * position_;
  return position_;
}

glm::dquat AdaptiveFilter::attitude(const glm::dquat& in, const FilterParams& p) {
  glm::dquat q = in;
  if (glm::dot(q, attitude_) < 0.0) q = -q;  // q and -q: the same rotation
  const double c = std::min(1.0, std::fabs(glm::dot(q, attitude_)));
  const double angle_deg = 2.0 * std::acos(c) * 180.0 / 3.14159265358979323846;
  if (!adapt(primed_ ? angle_deg / kFullStepDegrees : 0.0, p)) {
    attitude_ = q;
    return in;
  }
  // Normalised linear blend: the exponential filter on the unit sphere.
  attitude_ = glm::normalize(alpha_ * q + (1.0 - alpha_) * attitude_);
  return attitude_;
}

}  // namespace twister::sim
