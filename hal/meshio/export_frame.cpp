#include "export_frame.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace twister::meshio::internal {

glm::dmat3 rotation_between(glm::dvec3 from, glm::dvec3 to) {
  const glm::dvec3 f = glm::normalize(from);
  const glm::dvec3 t = glm::normalize(to);
  const double c = glm::dot(f, t);
  if (c > 1.0 - 1e-12) return glm::dmat3(1.0);
  glm::dvec3 axis;
  double angle = 0.0;
  if (c < -1.0 + 1e-12) {
    // Opposite: half a turn about an axis perpendicular to `to`.
    const glm::dvec3 other = std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    axis = glm::normalize(glm::cross(t, other));
    angle = M_PI;
  } else {
    axis = glm::normalize(glm::cross(f, t));
    angle = std::acos(std::clamp(c, -1.0, 1.0));
  }
  // Rodrigues: R = I cos + (1 - cos) a a^T + sin [a]x (column-major glm).
  const double co = std::cos(angle);
  const double si = std::sin(angle);
  glm::dmat3 r(co);
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) r[col][row] += (1.0 - co) * axis[row] * axis[col];
  }
  const glm::dmat3 cross_matrix(glm::dvec3(0, axis.z, -axis.y), glm::dvec3(-axis.z, 0, axis.x),
                                glm::dvec3(axis.y, -axis.x, 0));
  return r + si * cross_matrix;
}

hal::Expected<UprightFrame> upright_frame(const mesh::Mesh& mesh, glm::vec3 up, glm::dvec3 target) {
  const glm::dvec3 u(up);
  if (!std::isfinite(u.x) || !std::isfinite(u.y) || !std::isfinite(u.z) || glm::dot(u, u) < 1e-24) {
    return hal::make_error(StatusCode::invalid_argument,
                           "the up direction must be a finite, non-zero vector");
  }
  if (mesh.vertex_count() == 0) {
    return hal::make_error(StatusCode::invalid_argument, "the mesh has no vertices");
  }
  UprightFrame frame;
  frame.rotation = rotation_between(u, target);
  glm::dvec3 lo(1e300);
  glm::dvec3 hi(-1e300);
  for (std::uint32_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::dvec3 p = frame.rotation * glm::dvec3(mesh.position(i));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return hal::make_error(StatusCode::invalid_argument,
                             "vertex " + std::to_string(i) + " is not finite");
    }
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  frame.offset = -0.5 * (lo + hi);
  frame.lo = lo + frame.offset;
  frame.hi = hi + frame.offset;
  return frame;
}

}  // namespace twister::meshio::internal
