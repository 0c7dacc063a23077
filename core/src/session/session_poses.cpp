#include "twister/session/session_poses.hpp"

#include <glm/mat3x3.hpp>

namespace twister::session {

Status SessionPoses::set_hand(std::uint8_t hand, bool valid, const math::Frame& pose_in_world) {
  if (hand >= input::kHandCount) return StatusCode::out_of_range;
  if (!valid) {
    hands_[hand].valid = false;
    return ok_status();
  }
  if (!math::is_orthonormal(pose_in_world)) {
    hands_[hand].valid = false;
    return StatusCode::invalid_argument;
  }
  hands_[hand].valid = true;
  // W is rebuilt from U and V so that the journal (which stores O, U, V) replays
  // exactly the frame used live.
  hands_[hand].world = math::frame_from_uv(pose_in_world.origin, pose_in_world.u, pose_in_world.v);
  return ok_status();
}

math::Frame SessionPoses::hand_in_object(std::uint8_t hand) const {
  const math::Frame& world = hands_[hand].world;
  const glm::dmat3 r_t = glm::transpose(glm::dmat3(object_.u, object_.v, object_.w));
  return math::frame_from_uv(r_t * (world.origin - object_.origin), r_t * world.u, r_t * world.v);
}

}  // namespace twister::session
