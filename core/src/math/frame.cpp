#include "twister/math/frame.hpp"

#include <cmath>
#include <glm/geometric.hpp>

namespace twister::math {

Frame identity_frame(glm::dvec3 origin) {
  Frame f;
  f.origin = origin;
  return f;
}

Frame frame_from_uv(glm::dvec3 origin, glm::dvec3 u, glm::dvec3 v) {
  return Frame{origin, u, v, glm::cross(u, v)};
}

namespace {
bool finite(glm::dvec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
}  // namespace

bool is_orthonormal(const Frame& f, double tolerance) {
  if (!finite(f.origin) || !finite(f.u) || !finite(f.v) || !finite(f.w)) return false;
  const auto near = [tolerance](double a, double b) { return std::fabs(a - b) <= tolerance; };
  // Lengths, not squared lengths: "unit within 1e-6" as the warp contract states it.
  return near(glm::length(f.u), 1.0) && near(glm::length(f.v), 1.0) &&
         near(glm::length(f.w), 1.0) && near(glm::dot(f.u, f.v), 0.0) &&
         near(glm::dot(f.v, f.w), 0.0) && near(glm::dot(f.w, f.u), 0.0) &&
         glm::length(glm::cross(f.u, f.v) - f.w) <= tolerance;
}

}  // namespace twister::math
