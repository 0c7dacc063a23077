// Continuity check of successive poses (see pose_continuity.hpp).
#include "twister/tracker/pose_continuity.hpp"

#include <algorithm>
#include <cmath>

#include "twister/tracker/pose_conversion.hpp"

namespace twister::tracker {

PoseContinuity::PoseContinuity(const ContinuityLimits& limits, Units units, Format format)
    : limits_(limits), scale_(units == Units::inches ? 1.0 : 2.54), format_(format) {}

void PoseContinuity::reset() {
  reference_ = {};
  held_ = {};
  chain_ = {};
}

PoseContinuity::Sample PoseContinuity::sample_of(const FastrakPose& pose,
                                                 ports::TimestampUs now) const {
  Sample s;
  s.valid = true;
  s.t = now;
  s.position = glm::dvec3(pose.position[0], pose.position[1], pose.position[2]);
  if (auto r = tracker_rotation(pose, format_); r.ok()) {
    s.has_rotation = true;
    s.rotation = *r;
  }
  return s;
}

bool PoseContinuity::consistent(const Sample& from, const Sample& to) const {
  const double dt = static_cast<double>(std::max(to.t - from.t, limits_.min_interval_us)) / 1e6;
  if (limits_.max_speed_in_s > 0.0) {
    const double reach = (limits_.max_speed_in_s * dt + limits_.position_slack_in) * scale_;
    if (glm::length(to.position - from.position) > reach) return false;
  }
  if (limits_.max_turn_rate_deg_s > 0.0 && from.has_rotation && to.has_rotation) {
    // Angle of the relative rotation: trace(A^T B) = 1 + 2 cos(angle).
    const glm::dmat3 rel = glm::transpose(from.rotation) * to.rotation;
    const double c = std::clamp((rel[0][0] + rel[1][1] + rel[2][2] - 1.0) / 2.0, -1.0, 1.0);
    const double angle_deg = std::acos(c) * 180.0 / 3.14159265358979323846;
    if (angle_deg > limits_.max_turn_rate_deg_s * dt + limits_.angle_slack_deg) return false;
  }
  return true;
}

bool PoseContinuity::accept(const FastrakPose& pose, ports::TimestampUs now) {
  if (pose.station < 1 || pose.station > kMaxStations) return false;
  const std::size_t i = pose.station - 1u;
  const Sample s = sample_of(pose, now);
  Sample& ref = reference_[i];
  Sample& held = held_[i];
  int& chain = chain_[i];
  if (!ref.valid || consistent(ref, s)) {
    ref = s;
    held.valid = false;
    return true;
  }
  chain = held.valid && consistent(held, s) ? chain + 1 : 0;
  if (chain >= limits_.confirmations) {  // the jump is real
    ref = s;
    held.valid = false;
    return true;
  }
  held = s;
  return false;
}

}  // namespace twister::tracker
