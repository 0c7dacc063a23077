// MeshRenderer: draws the replica's mesh with OpenGL (3.3 core; 4.0 for the refined
// live preview) into an FBO (offscreen, readable) or the default framebuffer
// (window). The live stroke is applied in the shaders: per hand the screw constants
// (uniforms, the same terms as core's scalar kernel), the displacements of both
// hands summed. On a GL 4 context with a refinement threshold from the station the
// live preview is refined per frame by tessellation with the commit's criterion, so
// it is as smooth as the commit will be (mesh_shaders.hpp); otherwise the mesh's own
// vertices are warped (refining_live() says which). A stroke under a symmetry group is
// warped by a third program, every image of every hand with the plan's weights per image
// (mesh_renderer_symmetric.cpp; unrefined, both faces drawn). Crease-aware shading
// (crease_shading.hpp): sharp edges keep a normal per side; while warping, the
// shaders turn the normals with the warp. Weights tint the surface with each hand's
// colour (red hand 1, green hand 2). The model is drawn at the object pose; the
// camera (camera.hpp) frames it. Needs a current context.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "camera.hpp"
#include "gl_program.hpp"
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
  // New rest mesh with its shading (SceneReplica::shading()); resets weights and
  // frames the camera unless keep_camera.
  void set_mesh(const MeshData& mesh, const ShadedMesh& shaded, bool keep_camera);
  // The same, shaded here with the default crease angle.
  void set_mesh(const MeshData& mesh, bool keep_camera);
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
  // A stroke under a symmetry group whose entries are ready (LiveState::symmetric_gpu)
  // is warped by the symmetric program: its entries are uploaded once per grab (when
  // their version changes), the images' constants every call.
  void set_live(const LiveState* live);
  // Whether this renderer warps `live` in a shader (the plain or the symmetric program);
  // false: the display draws cpu_warp() (scodef, a group without the symmetric program
  // or whose entries do not fit: LiveState::symmetric_gpu not ready, or more entries
  // than the GL's texture buffers hold).
  bool warps_on_gpu(const LiveState& live) const;
  // The symmetric program compiled (GL 3.3 texture buffers and uniform blocks); `allow`
  // false keeps symmetric strokes on the CPU path (tests, benches: the reference).
  bool has_symmetric_shader() const { return symmetric_.id != 0; }
  void allow_symmetric_shader(bool allow) { allow_symmetric_ = allow; }
  // The context runs the refined live preview (GL 4 tessellation); `allow` false
  // keeps the GL 3.3 path (tests, --no-live-refine).
  bool can_refine_live() const { return refined_.id != 0; }
  void allow_live_refinement(bool allow) { allow_refinement_ = allow; }
  // The live stroke is drawn refined (a GL 4 context, a shader warp, a threshold).
  bool refining_live() const;
  // The surface the live preview draws, as triangles (3 corners each, object frame):
  // rest and warped positions, read back by transform feedback (tests, checks).
  struct Surface {
    std::vector<glm::vec3> rest;
    std::vector<glm::vec3> warped;
  };
  Surface capture_live_surface();
  // Back-face culling (issue 24's frame cost): a mesh that is closed, manifold and
  // consistently wound (ShadedMesh::facing) shows an eye outside it only the faces
  // turned towards it, so the others are not drawn while the eye and the near plane
  // are clear of the model's bounding sphere. Triangles a live stroke can reach and
  // a CPU-warped preview (scodef, set_positions) draw both faces: a warp may fold
  // the surface over. An open or inconsistently wound mesh always draws both faces.
  // `allow` false draws both faces always (the baseline of benches and tests).
  void allow_face_culling(bool allow) { allow_culling_ = allow; }
  // The rest of the mesh (what no live stroke reaches) is drawn culled this frame.
  bool culling_faces() const;
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
  std::size_t vertex_count() const { return mesh_vertices_; }       // the mesh's
  std::size_t drawn_vertex_count() const { return vertex_count_; }  // with crease splits
  int width() const { return width_; }
  int height() const { return height_; }
  Camera& camera() { return camera_; }
  const Camera& camera() const { return camera_; }
  // The rest mesh's bounding sphere (object frame).
  glm::vec3 model_centre() const { return centre_; }
  float model_radius() const { return radius_; }

 private:
  // Uniform locations of one program, looked up once in init().
  struct Uniforms {
    int view_proj = -1, model = -1, eye = -1, light0 = -1, light1 = -1, show_weights = -1;
    int hand_mask = -1, eps = -1, radius = -1, threshold = -1, max_level = -1;
    int tint[2] = {-1, -1};
    int hand_vec3[2][5] = {};  // u_axis, u_mid, u_chord, u_axc, u_shift of each hand
    int half[2] = {};
    int cot[2] = {};
    int grab[2] = {-1, -1};
  };
  struct Program {
    unsigned id = 0;
    Uniforms u;
  };
  void upload(unsigned buffer, const std::vector<float>& data, std::size_t floats_per_vertex);
  static Uniforms find_uniforms(unsigned program);
  void use(const Program& program);
  void create_fbo(int width, int height);
  // The per-vertex input of the mesh as the drawn vertices' (crease splits copied).
  std::vector<float> drawn(const std::vector<float>& per_vertex, std::size_t columns) const;
  // The triangles the stroke's balls can reach first, in live_ebo_ (live_reached_
  // of them): only those go through tessellation; kept per grab points and radius.
  void split_live_triangles();
  // Culls the faces `facing` hides (GL_CULL_FACE), or none.
  static void cull(Facing facing);
  // Draws (and with `feedback`, captures) indices [first, first + count) of the
  // bound element buffer with `program`.
  void draw_range(const Program& program, bool patches, std::size_t first, std::size_t count);
  // The symmetric program, its texture buffers and uniform block (mesh_renderer_symmetric.cpp).
  void init_symmetric(const ShaderSources& sources);
  void delete_symmetric();
  bool symmetric_fits(const LiveState& live) const;
  void set_symmetric(const LiveState& live);
  void bind_symmetric() const;
  // The program drawing the live stroke's unrefined triangles.
  const Program& live_program() const { return sym_live_ ? symmetric_ : plain_; }

  Program plain_;
  Program refined_;    // 0 without GL 4 tessellation
  Program symmetric_;  // 0 without texture buffers / uniform blocks
  bool allow_symmetric_ = true;
  bool sym_live_ = false;  // the live stroke is drawn by symmetric_
  // Entries (RGBA32F), their images (R8UI): buffers and their texture views; the
  // images' uniform block.
  std::array<unsigned, 2> sym_buffers_{};
  std::array<unsigned, 2> sym_textures_{};
  unsigned sym_block_ = 0;
  int sym_entries_loc_ = -1;
  int sym_images_loc_ = -1;
  std::size_t max_texels_ = 0;     // GL_MAX_TEXTURE_BUFFER_SIZE
  std::uint64_t sym_version_ = 0;  // SymmetricLive::version uploaded (0: none)
  bool allow_refinement_ = true;
  bool allow_culling_ = true;
  bool cpu_live_ = false;          // a live stroke warped on the CPU (scodef)
  bool positions_warped_ = false;  // set_positions since the last set_mesh
  float max_level_ = 1.0F;
  unsigned vao_ = 0;
  // Positions, weights, normals, gradient 1, gradient 2, symmetric spans (attributes 0..5).
  std::array<unsigned, 6> vbo_{};
  unsigned ebo_ = 0;
  unsigned fbo_ = 0;
  unsigned color_rb_ = 0;
  unsigned depth_rb_ = 0;
  int width_ = 0;
  int height_ = 0;
  ShadedMesh shaded_;             // drawn vertices of the current mesh
  std::vector<float> positions_;  // theirs, as uploaded (x y z each)
  unsigned live_ebo_ = 0;
  std::size_t live_reached_ = 0;  // triangles (first in live_ebo_) the balls can reach
  std::array<glm::vec3, 2> split_grab_{};
  float split_radius_ = -1.0F;  // < 0: live_ebo_ is stale
  int split_mask_ = 0;
  std::size_t index_count_ = 0;
  std::size_t vertex_count_ = 0;
  std::size_t mesh_vertices_ = 0;
  glm::vec3 centre_{0.0F};
  float radius_ = 1.0F;
  Camera camera_;
  glm::mat4 model_{1.0F};
  // The live stroke: per hand axis, mid, chord, axis x chord, shift (3 each), half
  // angle, cot half; grab points, radius, the commit's threshold.
  float hands_[2][17] = {};
  int hand_mask_ = 0;
  std::array<glm::vec3, 2> grab_{};
  float stroke_radius_ = 1.0F;
  float threshold_ = 0.0F;
  bool show_weights_ = false;
  std::array<std::uint8_t, 2> colour_hand_{0, 1};
};

}  // namespace twister::bridge
