#include "twister/session/object_mover.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace twister::session {
namespace {

glm::dmat3 axes(const math::Frame& f) { return glm::dmat3(f.u, f.v, f.w); }

}  // namespace

void ObjectMover::begin(std::uint8_t hand) {
  moving_ = true;
  hand_ = hand;
  hand_start_ = poses_.hand_in_world(hand);
  object_start_ = poses_.object();
}

void ObjectMover::follow() {
  if (moving_ && poses_.valid(hand_)) poses_.set_object(moved_object());
}

Result<ObjectMove> ObjectMover::commit() {
  if (!moving_) return StatusCode::failed_precondition;
  moving_ = false;
  poses_.set_object(moved_object());
  return ObjectMove{hand_, object_start_, poses_.object()};
}

bool ObjectMover::cancel() {
  if (!moving_) return false;
  moving_ = false;
  poses_.set_object(object_start_);
  return true;
}

math::Frame ObjectMover::moved_object() const {
  const math::Frame& now = poses_.hand_in_world(hand_);
  const glm::dmat3 delta = axes(now) * glm::transpose(axes(hand_start_));
  const glm::dvec3 origin = delta * (object_start_.origin - hand_start_.origin) + now.origin;
  // Re-orthonormalise so rounding cannot accumulate over many moves.
  const glm::dvec3 u = glm::normalize(delta * object_start_.u);
  const glm::dvec3 v0 = delta * object_start_.v;
  const glm::dvec3 v = glm::normalize(v0 - glm::dot(v0, u) * u);
  return math::frame_from_uv(origin, u, v);
}

}  // namespace twister::session
