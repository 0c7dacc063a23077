// WorkspaceFraming: what the kiosk and offscreen cameras keep in view when the
// station reports where the hands work (link `workspace`, protocol 5): a sphere
// around the working volume and the model, grown smoothly to keep both cursors in
// the picture. No GL (unit-tested alone).
//
// A cursor that leaves the framed sphere (with a margin) raises the sphere it
// should be: the smallest sphere holding the current one and the cursor's margin
// ball. The framing moves a fraction of the way there per update, so it grows over
// a few updates instead of jumping with the hand, and it never shrinks (a hand
// that comes back does not make the model breathe).
#pragma once

#include <glm/vec3.hpp>
#include <span>

namespace twister::bridge {

struct Sphere {
  glm::vec3 centre{0.0F};
  float radius = 0.0F;
};

// The smallest sphere holding `a` and `b` (b may have radius 0: a point).
Sphere enclose(const Sphere& a, const Sphere& b);

class WorkspaceFraming {
 public:
  // Of the required sphere per update (1: jump there at once).
  static constexpr float kEase = 0.25F;
  // Around each cursor, as a fraction of the framed radius.
  static constexpr float kCursorMargin = 0.12F;

  // The working volume (world box) and the model's bounding sphere (world): the
  // framing grows to hold them (the first call sets it).
  void hold(glm::vec3 volume_min, glm::vec3 volume_max, const Sphere& model);
  // One update with the cursors (world): eases towards a sphere that holds them.
  // True when the framing moved.
  bool follow(std::span<const glm::vec3> cursors);
  bool active() const { return active_; }
  const Sphere& sphere() const { return sphere_; }
  void clear() { active_ = false; }

 private:
  bool ease_to(const Sphere& goal);

  bool active_ = false;
  Sphere sphere_{};
};

}  // namespace twister::bridge
