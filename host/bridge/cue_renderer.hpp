// CueRenderer: draws a CueScene (cue_geometry.hpp) over the mesh in the current
// framebuffer, with the mesh's depth: the glyph axes, screw axes, trajectories and
// object frame solid where visible and faded where the model hides them (so a
// sculptor sees an axis through the model), the spheres of influence translucent
// (front faces, no depth write), the hand cursors on top of everything.
// Needs a current context; init() once, draw() per frame after the mesh.
#pragma once

#include <glm/mat4x4.hpp>

#include "cue_geometry.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

class CueRenderer {
 public:
  CueRenderer() = default;
  ~CueRenderer();
  CueRenderer(const CueRenderer&) = delete;
  CueRenderer& operator=(const CueRenderer&) = delete;
  // Error not_supported: the shader does not compile or link.
  hal::Expected<void> init();
  void draw(const CueScene& scene, const glm::mat4& view_proj);

 private:
  void draw_mesh(const CueMesh& mesh, float alpha_scale);

  unsigned program_ = 0;
  unsigned vao_ = 0;
  unsigned vbo_pos_ = 0;
  unsigned vbo_colour_ = 0;
  unsigned ebo_ = 0;
  int u_view_proj_ = -1;
  int u_alpha_ = -1;
};

}  // namespace twister::bridge
