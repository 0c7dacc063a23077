// MeshRenderer: draws the replica's mesh with OpenGL 3.3 core into an FBO
// (offscreen, readable) or the default framebuffer (window). The live stroke is
// applied in the vertex shader: per vertex the two weights (attribute), per hand
// the screw constants (uniforms, the same terms as core's scalar kernel), the
// displacements of both hands summed. Smooth shading from vertex normals (the
// replica's); while warping, the shader turns them with the warp (mesh_shaders.hpp).
// Weights tint the surface with each hand's colour (red hand 1, green hand 2).
// The model is drawn at the object pose; the camera (camera.hpp) frames it.
// Needs a current context.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "camera.hpp"
#include "png_writer.hpp"
#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"
#include "twister/math/frame.hpp"

namespace twister::bridge {

// The hands' colours (session hand 0 = hand 1 red, 1 = hand 2 green), RGB 0..1.
inline constexpr std::array<std::array<float, 3>, 2> kHandColours{
    {{0.90F, 0.12F, 0.10F}, {0.12F, 0.80F, 0.20F}}};

class MeshRenderer {
 public:
  MeshRenderer() = default;
  ~MeshRenderer();
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;
  // Compiles the shaders; with `offscreen`, renders into a width x height FBO.
  // Error not_supported: a shader does not compile or link, or the FBO is incomplete.
  hal::Expected<void> init(int width, int height, bool offscreen, const ViewConfig& view);
  // New rest mesh with its vertex normals (3 per vertex; computed here when empty);
  // resets weights and frames the camera unless keep_camera.
  void set_mesh(const MeshData& mesh, const std::vector<float>& normals, bool keep_camera);
  void set_mesh(const MeshData& mesh, bool keep_camera) { set_mesh(mesh, {}, keep_camera); }
  // New positions for the mesh of the last set_mesh (same vertex count; triangles,
  // weights and camera kept): the CPU-warped preview; normals recomputed from them.
  void set_positions(const MeshData& mesh);
  // Weight columns (per vertex) and the session hand whose colour each one shows.
  void set_weights(const std::vector<float>& w1, const std::vector<float>& w2,
                   std::array<std::uint8_t, 2> colour_hand = {0, 1});
  // Per-vertex weight gradients (3 floats each) of the live stroke's columns (for
  // the warped normals); empty: zero.
  void set_gradients(const std::vector<float>& g1, const std::vector<float>& g2);
  // Hand uniforms from the replica's live stroke (scodef: no shader warp, see set_mesh).
  void set_live(const LiveState* live);
  // Tint by the weights (before a grab, and during one).
  void set_show_weights(bool show) { show_weights_ = show; }
  // The object frame in the world (the model matrix).
  void set_object_pose(const math::Frame& pose);
  const glm::mat4& model_matrix() const { return model_; }
  // Frame = begin_frame (bind, viewport, clear) + draw_mesh + end_frame (glFinish);
  // draw() does all three. Cues and the HUD draw between draw_mesh and end_frame.
  void begin_frame();
  void draw_mesh();
  void end_frame();
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
  Camera& camera() { return camera_; }
  const Camera& camera() const { return camera_; }
  // The rest mesh's bounding sphere (object frame).
  glm::vec3 model_centre() const { return centre_; }
  float model_radius() const { return radius_; }

 private:
  void upload(unsigned buffer, const std::vector<float>& data, std::size_t floats_per_vertex);
  void find_uniforms();
  void create_fbo(int width, int height);

  unsigned program_ = 0;
  unsigned vao_ = 0;
  // Positions, weights, normals, gradient 1, gradient 2 (attributes 0..4).
  std::array<unsigned, 5> vbo_{};
  unsigned ebo_ = 0;
  unsigned fbo_ = 0;
  unsigned color_rb_ = 0;
  unsigned depth_rb_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::size_t index_count_ = 0;
  std::size_t vertex_count_ = 0;
  glm::vec3 centre_{0.0F};
  float radius_ = 1.0F;
  Camera camera_;
  glm::mat4 model_{1.0F};
  // Per hand: axis, mid, chord, axis x chord, shift (3 each), half angle, cot half.
  float hands_[2][17] = {};
  int hand_mask_ = 0;
  bool show_weights_ = false;
  std::array<std::uint8_t, 2> colour_hand_{0, 1};
  // Uniform locations, looked up once in init().
  struct Uniforms {
    int view_proj = -1, model = -1, eye = -1, light0 = -1, light1 = -1, show_weights = -1;
    int hand_mask = -1, eps = -1;
    int tint[2] = {-1, -1};
    int hand_vec3[2][5] = {};  // u_axis, u_mid, u_chord, u_axc, u_shift of each hand
    int half[2] = {};
    int cot[2] = {};
  } uniforms_;
};

}  // namespace twister::bridge
