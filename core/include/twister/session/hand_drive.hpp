// HandDrive: how one hand's motion becomes its end pose in the stroke's WarpPlan
// (docs/interaction.md "Clutch", docs/unwrap.md). Per session hand:
//   - the clutch: a disengaged hand (freeze held) does not drive the warp, its end
//     pose stays on its start pose, whatever the hand does;
//   - the turn: a TurnTracker follows the hand's rotation since the segment's start
//     sample by sample; with TurnTracking::unwrapped the hand's screw goes the long
//     way round once it has turned past a half turn (long_turn()), and past the limit
//     the end pose holds (the last pose within the limit) until the hand turns back;
//     with TurnTracking::minimal the end pose is always the hand's pose (the minimal
//     screw of docs/math.md §2: at most a half turn, a 240-degree turn warps as -120).
// Poses in the object frame (the stroke's frame). No allocation; not thread-safe.
#pragma once

#include <cstdint>
#include <numbers>

#include "twister/math/frame.hpp"
#include "twister/math/turn_tracker.hpp"

namespace twister::session {

enum class TurnTracking : std::uint8_t {
  minimal,    // the paper's minimal screw per stroke (at most 180 degrees)
  unwrapped,  // turns tracked continuously, up to TurnConfig::limit_rad
};
// "minimal" | "unwrapped".
const char* turn_tracking_name(TurnTracking tracking);

inline constexpr double kDegree = std::numbers::pi / 180.0;
inline constexpr double kDefaultTurnLimitRad = 330.0 * kDegree;
// Limits the station accepts: from a half turn up to 350 degrees, where a decayed
// point's helix is already 11 times as wide as the hand's sideways move (the screw
// degenerates at a full turn; docs/unwrap.md).
inline constexpr double kMinTurnLimitRad = 180.0 * kDegree;
inline constexpr double kMaxTurnLimitRad = 350.0 * kDegree;

struct TurnConfig {
  TurnTracking tracking = TurnTracking::unwrapped;
  double limit_rad = kDefaultTurnLimitRad;  // clamped to [kMinTurnLimitRad, kMaxTurnLimitRad]
};

// What follow() changed about the limit.
enum class TurnLimitChange : std::uint8_t { none, reached, left };

class HandDrive {
 public:
  explicit HandDrive(const TurnConfig& config = {});

  // A segment (re)starts at `pose`: start = end = pose, no turn, not at the limit.
  void start(const math::Frame& pose);
  // The hand's current pose (engaged hands only; a disengaged hand ignores it).
  TurnLimitChange follow(const math::Frame& pose);
  // Disengaging puts the end pose back on the start pose (the hand's warp is the
  // identity until start() re-engages it from a new pose).
  void set_engaged(bool engaged);

  bool engaged() const { return engaged_; }
  const math::Frame& start_pose() const { return start_; }
  const math::Frame& end_pose() const { return end_; }
  // The end pose's screw goes the long way round (past a half turn).
  bool long_turn() const { return long_turn_; }
  // How far the hand has turned since start(), whichever way (any number of turns).
  double turned_rad() const { return tracker_.turned_rad(); }
  // The end pose is held because the hand turned past the limit.
  bool at_limit() const { return at_limit_; }
  // The limit in force: limit_rad (unwrapped) or a half turn (minimal).
  double limit_rad() const;
  const TurnConfig& config() const { return config_; }

 private:
  TurnConfig config_;
  math::TurnTracker tracker_{};
  math::Frame start_{};
  math::Frame end_{};
  bool engaged_ = true;
  bool long_turn_ = false;
  bool at_limit_ = false;
};

}  // namespace twister::session
