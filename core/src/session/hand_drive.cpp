#include "twister/session/hand_drive.hpp"

#include <algorithm>
#include <cmath>

namespace twister::session {

const char* turn_tracking_name(TurnTracking tracking) {
  switch (tracking) {
    case TurnTracking::minimal:
      return "minimal";
    case TurnTracking::unwrapped:
      return "unwrapped";
  }
  return "unknown";
}

HandDrive::HandDrive(const TurnConfig& config) : config_(config) {
  const double limit = std::isfinite(config.limit_rad) ? config.limit_rad : kDefaultTurnLimitRad;
  config_.limit_rad = std::clamp(limit, kMinTurnLimitRad, kMaxTurnLimitRad);
}

double HandDrive::limit_rad() const {
  return config_.tracking == TurnTracking::unwrapped ? config_.limit_rad : std::numbers::pi;
}

void HandDrive::start(const math::Frame& pose) {
  start_ = pose;
  end_ = pose;
  tracker_.reset();
  long_turn_ = false;
  at_limit_ = false;
}

void HandDrive::set_engaged(bool engaged) {
  engaged_ = engaged;
  if (!engaged) {
    end_ = start_;
    long_turn_ = false;
    at_limit_ = false;
  }
}

TurnLimitChange HandDrive::follow(const math::Frame& pose) {
  if (!engaged_) return TurnLimitChange::none;
  tracker_.follow(start_, pose);
  if (config_.tracking == TurnTracking::minimal) {
    end_ = pose;
    return TurnLimitChange::none;
  }
  if (tracker_.turned_rad() > config_.limit_rad) {
    // Hold the last pose within the limit; the tracker keeps following, so the hand
    // comes back exactly where it turned out (also after turning on past 360).
    if (at_limit_) return TurnLimitChange::none;
    at_limit_ = true;
    return TurnLimitChange::reached;
  }
  end_ = pose;
  long_turn_ = tracker_.long_way();
  if (!at_limit_) return TurnLimitChange::none;
  at_limit_ = false;
  return TurnLimitChange::left;
}

}  // namespace twister::session
