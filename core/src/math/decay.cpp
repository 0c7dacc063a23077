#include "twister/math/decay.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace twister::math {

double decay(double distance, double radius) {
  if (!(distance < radius)) return 0.0;
  const double c = std::cos(0.5 * std::numbers::pi * distance / radius);
  return c * c;
}

glm::dvec3 squash_point(glm::dvec3 grab, glm::dvec3 other, double radius, glm::dvec3 p) {
  const glm::dvec3 oq = other - grab;
  const double s = glm::length(oq);
  if (!(s < radius) || s <= 0.0) return p;
  const double proj = glm::dot(p - grab, oq);
  if (proj < 0.0) return p;
  // Stretch by r/s along OQ so that the ball's half towards Q ends at Q.
  return p + (proj / s) * ((radius - s) / s) * (oq / s);
}

double hand_weight(glm::dvec3 grab, const glm::dvec3* other, double radius, glm::dvec3 p) {
  const glm::dvec3 q = other != nullptr ? squash_point(grab, *other, radius, p) : p;
  return decay(glm::length(q - grab), radius);
}

}  // namespace twister::math
