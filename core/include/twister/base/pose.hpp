// Pose: the project's one pose type. A rigid frame: origin and orthonormal, right-handed
// axes U, V, W (W = U x V), doubles, in whatever frame and unit its owner states (the
// station: metres, world or object frame). math::Frame is this type; the tracker makes
// one from a Fastrak record (tracker::to_station_frame), the link and the journal carry
// it and encode it at their edges only (the link: origin, U, V, W; the journal: origin,
// U, V, with W rebuilt as U x V when read). Plain data: no heap, no invariant checks
// (math::is_orthonormal checks one).
#pragma once

#include <glm/vec3.hpp>

namespace twister {

struct Pose {
  glm::dvec3 origin{0.0};
  glm::dvec3 u{1.0, 0.0, 0.0};
  glm::dvec3 v{0.0, 1.0, 0.0};
  glm::dvec3 w{0.0, 0.0, 1.0};
  friend bool operator==(const Pose&, const Pose&) = default;
};

}  // namespace twister
