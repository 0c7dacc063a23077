#include "framing.hpp"

#include <algorithm>
#include <glm/geometric.hpp>

namespace twister::bridge {

Sphere enclose(const Sphere& a, const Sphere& b) {
  const glm::vec3 d = b.centre - a.centre;
  const float dist = glm::length(d);
  if (dist + b.radius <= a.radius) return a;
  if (dist + a.radius <= b.radius) return b;
  const float radius = 0.5F * (dist + a.radius + b.radius);
  return {a.centre + ((radius - a.radius) / dist) * d, radius};
}

void WorkspaceFraming::hold(glm::vec3 volume_min, glm::vec3 volume_max, const Sphere& model) {
  const Sphere volume{0.5F * (volume_min + volume_max),
                      0.5F * glm::length(volume_max - volume_min)};
  const Sphere both = enclose(volume, model);
  if (!active_) {
    sphere_ = both;
    active_ = true;
    return;
  }
  sphere_ = enclose(sphere_, both);
}

bool WorkspaceFraming::follow(std::span<const glm::vec3> cursors) {
  if (!active_) return false;
  Sphere goal = sphere_;
  for (const glm::vec3& c : cursors) goal = enclose(goal, {c, kCursorMargin * sphere_.radius});
  return ease_to(goal);
}

bool WorkspaceFraming::ease_to(const Sphere& goal) {
  if (goal.radius <= sphere_.radius * (1.0F + 1e-5F) &&
      glm::length(goal.centre - sphere_.centre) <= 1e-6F * sphere_.radius) {
    return false;
  }
  // Part of the way; the eased sphere still holds the current one (it never shrinks).
  const Sphere step{sphere_.centre + kEase * (goal.centre - sphere_.centre),
                    sphere_.radius + kEase * (goal.radius - sphere_.radius)};
  sphere_ = enclose(step, sphere_);
  return true;
}

}  // namespace twister::bridge
