// MeshRenderer: draws the replica's mesh with OpenGL 3.3 core into an FBO
// (offscreen, readable) or the default framebuffer (window). The live stroke is
// applied in the vertex shader: per vertex the two weights (attribute), per hand
// the screw constants (uniforms, the same terms as core's scalar kernel), the
// displacements of both hands summed. Lit with per-pixel face normals (derivatives
// of the warped position, so shading follows the warp); weights tint the surface
// red (hand 1) and green (hand 2) as in the paper's figures.
// The camera frames the rest mesh's bounding sphere. Needs a current context.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

struct ViewConfig {
  float azimuth_deg = 200.0F;   // around the up axis
  float elevation_deg = 25.0F;  // above the horizontal
  float zoom_out = 1.0F;        // camera distance x this (room for a model that grows)
  // Object-frame up (tracker frame: +Z points down, so up is -Z).
  float up[3] = {0.0F, 0.0F, -1.0F};
};

class MeshRenderer {
 public:
  ~MeshRenderer();
  // Compiles the shaders; with `offscreen`, renders into a width x height FBO.
  // Error not_supported: a shader does not compile or link, or the FBO is incomplete.
  hal::Expected<void> init(int width, int height, bool offscreen, const ViewConfig& view);
  // New rest mesh (positions + triangles); resets weights and recentres the camera
  // unless keep_camera.
  void set_mesh(const MeshData& mesh, bool keep_camera);
  // New positions for the mesh of the last set_mesh (same vertex count; triangles,
  // weights and camera kept): the CPU-warped preview.
  void set_positions(const MeshData& mesh);
  void set_weights(const std::vector<float>& w1, const std::vector<float>& w2);
  // Hand uniforms from the replica's live stroke (scodef: no shader warp, see set_mesh).
  void set_live(const LiveState* live);
  // Tint by the weights even without a shader warp (scodef / CPU-warped uploads).
  void set_show_weights(bool show) { show_weights_ = show; }
  void draw();
  // Window resized (default framebuffer only; the offscreen FBO keeps its size).
  void resize(int width, int height) {
    if (fbo_ == 0) {
      width_ = width;
      height_ = height;
    }
  }
  // RGBA rows top to bottom.
  std::vector<std::uint8_t> read_rgba() const;
  std::size_t vertex_count() const { return vertex_count_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned program_ = 0;
  unsigned vao_ = 0;
  unsigned vbo_pos_ = 0;
  unsigned vbo_weight_ = 0;
  unsigned ebo_ = 0;
  unsigned fbo_ = 0;
  unsigned color_rb_ = 0;
  unsigned depth_rb_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::size_t index_count_ = 0;
  std::size_t vertex_count_ = 0;
  float center_[3] = {0, 0, 0};
  float radius_ = 1.0F;
  ViewConfig view_{};
  // Per hand: axis, mid, chord, axis x chord, shift (3 each), half angle, cot half.
  float hands_[2][17] = {};
  int hand_mask_ = 0;
  bool show_weights_ = false;
  // Uniform locations, looked up once in init().
  struct Uniforms {
    int mvp = -1, eye = -1, light0 = -1, light1 = -1, show_weights = -1, hand_mask = -1;
    int hand_vec3[2][5] = {};  // u_axis, u_mid, u_chord, u_axc, u_shift of each hand
    int half[2] = {};
    int cot[2] = {};
  } uniforms_;
};

// Writes RGBA rows (top to bottom) as PNG (compression 1). Error io_error naming
// the path when it cannot be written.
hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba);

}  // namespace twister::bridge
