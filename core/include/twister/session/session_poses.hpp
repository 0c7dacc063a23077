// SessionPoses: where the hands and the object are. Per hand the latest sample's
// validity and the last valid pose (world frame; a lost hand keeps it, so a held warp
// or move can finish there); the object's pose in the world (the mesh lives in the
// object frame, see docs/interaction.md "Move object").
// Warps are computed on hand poses in the object frame: hand_in_object() is that
// conversion, evaluated with the object pose of the moment it is called.
// No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/input/button_map.hpp"
#include "twister/math/frame.hpp"

namespace twister::session {

class SessionPoses {
 public:
  // Latest sample of a hand. An invalid sample means "lost".
  // out_of_range: hand >= kHandCount (ignored). invalid_argument: valid but not an
  // orthonormal frame (treated as lost).
  Status set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world);

  // hand < kHandCount.
  bool valid(std::uint8_t hand) const { return hands_[hand].valid; }
  const math::Frame& hand_in_world(std::uint8_t hand) const { return hands_[hand].world; }
  math::Frame hand_in_object(std::uint8_t hand) const;

  const math::Frame& object() const { return object_; }
  void set_object(const math::Frame& pose_in_world) { object_ = pose_in_world; }

 private:
  struct HandTrack {
    bool valid = false;
    math::Frame world{};  // last valid pose
  };

  std::array<HandTrack, input::kHandCount> hands_{};
  math::Frame object_{};
};

}  // namespace twister::session
