// Camera: the display's view of the world (the object pose places the mesh in it).
// An orbit camera about a target: azimuth around the up axis, elevation above the
// horizontal, a distance that frames the model's bounding sphere (zoom 1), and a
// pan that moves the target in the view plane. The window's mouse and keys turn
// it; a kiosk keeps the fixed ViewConfig of its config file. Pixels: x right, y
// down, origin at the top-left corner (as in the PNGs and read_rgba()).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>

namespace twister::bridge {

struct ViewConfig {
  float azimuth_deg = 200.0F;   // around the up axis
  float elevation_deg = 25.0F;  // above the horizontal
  float zoom = 1.0F;            // > 1 comes closer (distance = framing distance / zoom)
  float fov_deg = 35.0F;        // vertical field of view
  // World up (tracker frame: +Z points down, so up is -Z).
  float up[3] = {0.0F, 0.0F, -1.0F};
  // A fixed look-at point (world, metres) instead of the model's centre.
  bool has_target = false;
  float target[3] = {0.0F, 0.0F, 0.0F};
};

class Camera {
 public:
  explicit Camera(const ViewConfig& view = {}) : view_(view) { reset(); }
  void set_view(const ViewConfig& view) {
    view_ = view;
    reset();
  }
  const ViewConfig& view() const { return view_; }
  // A new world up (the station's work frame), angles and framing kept.
  void set_up(glm::vec3 up) {
    view_.up[0] = up.x;
    view_.up[1] = up.y;
    view_.up[2] = up.z;
  }
  // Frames a bounding sphere in the world (the model): the target is its centre
  // unless the view fixes one, the distance fits it in the view at zoom 1.
  void frame(glm::vec3 centre, float radius);
  // Back to the view configuration (angles, zoom, no pan) around the framing.
  void reset();
  void orbit(float d_azimuth_deg, float d_elevation_deg);  // elevation kept within +-89
  void zoom(float factor);                                 // > 1 comes closer
  // Moves the target by a fraction of the view's height (dx right, dy up).
  void pan(float dx, float dy);

  glm::vec3 eye() const;
  glm::vec3 target() const { return centre_ + pan_; }
  glm::vec3 up() const;
  // Unit vector from the target towards the eye.
  glm::vec3 direction() const;
  float distance() const;
  // The near clipping plane's distance from the eye (projection()).
  float near_distance() const;
  float scene_radius() const { return radius_; }
  glm::mat4 view_matrix() const;
  glm::mat4 projection(int width, int height) const;
  // The pixel of a world point; nullopt behind the camera.
  std::optional<glm::vec2> project(glm::vec3 world, int width, int height) const;

 private:
  ViewConfig view_;
  glm::vec3 centre_{0.0F};
  float radius_ = 1.0F;
  float azimuth_deg_ = 0.0F;
  float elevation_deg_ = 0.0F;
  float zoom_ = 1.0F;
  glm::vec3 pan_{0.0F};
};

}  // namespace twister::bridge
