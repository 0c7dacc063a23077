#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace twister::bridge {

void Camera::frame(glm::vec3 centre, float radius) {
  centre_ =
      view_.has_target ? glm::vec3(view_.target[0], view_.target[1], view_.target[2]) : centre;
  radius_ = std::max(radius, 1e-6F);
}

void Camera::reset() {
  azimuth_deg_ = view_.azimuth_deg;
  elevation_deg_ = std::clamp(view_.elevation_deg, -89.0F, 89.0F);
  zoom_ = std::clamp(view_.zoom, 0.05F, 50.0F);
  pan_ = glm::vec3(0.0F);
  if (view_.has_target) centre_ = glm::vec3(view_.target[0], view_.target[1], view_.target[2]);
}

void Camera::orbit(float d_azimuth_deg, float d_elevation_deg) {
  azimuth_deg_ = std::fmod(azimuth_deg_ + d_azimuth_deg, 360.0F);
  elevation_deg_ = std::clamp(elevation_deg_ + d_elevation_deg, -89.0F, 89.0F);
}

void Camera::zoom(float factor) {
  if (factor > 0.0F) zoom_ = std::clamp(zoom_ * factor, 0.05F, 50.0F);
}

void Camera::pan(float dx, float dy) {
  // One unit is the view's height at the target's distance.
  const float height = 2.0F * distance() * std::tan(0.5F * glm::radians(view_.fov_deg));
  const glm::vec3 right = glm::normalize(glm::cross(-direction(), up()));
  const glm::vec3 screen_up = glm::cross(right, -direction());
  pan_ += height * (dx * right + dy * screen_up);
}

glm::vec3 Camera::up() const {
  const glm::vec3 u(view_.up[0], view_.up[1], view_.up[2]);
  const float len = glm::length(u);
  return len > 1e-6F ? u / len : glm::vec3(0.0F, 0.0F, -1.0F);
}

glm::vec3 Camera::direction() const {
  const glm::vec3 u = up();
  // A horizontal reference perpendicular to up, then azimuth/elevation about it.
  const glm::vec3 side =
      glm::normalize(glm::cross(u, std::abs(u.x) < 0.9F ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 fwd = glm::cross(side, u);
  const float az = glm::radians(azimuth_deg_);
  const float el = glm::radians(elevation_deg_);
  return std::cos(el) * (std::cos(az) * fwd + std::sin(az) * side) + std::sin(el) * u;
}

float Camera::distance() const {
  const float fov = glm::radians(view_.fov_deg);
  return 1.1F * radius_ / std::sin(0.5F * fov) / zoom_;
}

glm::vec3 Camera::eye() const { return target() + distance() * direction(); }

glm::mat4 Camera::view_matrix() const { return glm::lookAt(eye(), target(), up()); }

float Camera::near_distance() const {
  // Near and far around the model (plus room for the cues around it).
  const float d = distance();
  return std::max(d - 4.0F * radius_, 0.02F * d);
}

glm::mat4 Camera::projection(int width, int height) const {
  const float d = distance();
  return glm::perspective(glm::radians(view_.fov_deg),
                          static_cast<float>(width) / static_cast<float>(std::max(height, 1)),
                          near_distance(), d + 4.0F * radius_);
}

std::optional<glm::vec2> Camera::project(glm::vec3 world, int width, int height) const {
  const glm::vec4 clip = projection(width, height) * view_matrix() * glm::vec4(world, 1.0F);
  if (clip.w <= 0.0F) return std::nullopt;
  const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
  return glm::vec2((ndc.x + 1.0F) * 0.5F * static_cast<float>(width),
                   (1.0F - ndc.y) * 0.5F * static_cast<float>(height));
}

}  // namespace twister::bridge
