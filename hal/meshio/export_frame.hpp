// Upright and centred (private to meshio): the rotation that takes the model's up to
// a format's up (the smallest one, about their cross product; half a turn about a
// perpendicular axis when they are opposite) and the offset that then puts the
// bounding box's centre at the origin.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "twister/hal/expected.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::meshio::internal {

struct UprightFrame {
  glm::dmat3 rotation{1.0};
  glm::dvec3 offset{0.0};  // added after the rotation
  glm::dvec3 lo{0.0};      // the bounding box after rotation and offset
  glm::dvec3 hi{0.0};

  glm::dvec3 apply(glm::dvec3 p) const { return rotation * p + offset; }
};

// The rotation taking `from` to `to` (both non-zero; normalised here).
glm::dmat3 rotation_between(glm::dvec3 from, glm::dvec3 to);

// For `mesh` with its up `up` and the format's up `target`. invalid_argument: `up`
// zero or not finite, no vertices, a position not finite.
hal::Expected<UprightFrame> upright_frame(const mesh::Mesh& mesh, glm::vec3 up, glm::dvec3 target);

}  // namespace twister::meshio::internal
