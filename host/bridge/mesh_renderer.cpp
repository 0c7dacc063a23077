#include "mesh_renderer.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "crease_shading.hpp"
#include "gl_program.hpp"
#include "mesh_shaders.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::bridge {
namespace {

// x0 y0 z0 x1 y1 z1 ... of the drawn vertices, for the position buffer.
std::vector<float> interleaved_positions(const MeshData& mesh, const ShadedMesh& shaded) {
  std::vector<float> pos(3 * shaded.vertex_count());
  for (std::size_t i = 0; i < shaded.vertex_count(); ++i) {
    const std::uint32_t v = shaded.source[i];
    pos[3 * i] = mesh.x[v];
    pos[3 * i + 1] = mesh.y[v];
    pos[3 * i + 2] = mesh.z[v];
  }
  return pos;
}

constexpr const char* kGlsl330 = "#version 330 core\n";
constexpr const char* kGlsl400 = "#version 400 core\n";
// Transform feedback of both programs (capture_live_surface).
constexpr std::array<const char*, 2> kFeedback{"v_rest", "v_object"};

}  // namespace

MeshRenderer::~MeshRenderer() {
  if (plain_.id != 0) glDeleteProgram(plain_.id);
  if (refined_.id != 0) glDeleteProgram(refined_.id);
  delete_symmetric();
  if (vao_ != 0) {
    glDeleteBuffers(static_cast<GLsizei>(vbo_.size()), vbo_.data());
    glDeleteBuffers(1, &ebo_);
    glDeleteBuffers(1, &live_ebo_);
    glDeleteVertexArrays(1, &vao_);
  }
  if (fbo_ != 0) glDeleteFramebuffers(1, &fbo_);
  const GLuint rbs[] = {color_rb_, depth_rb_};
  if (color_rb_ != 0) glDeleteRenderbuffers(2, rbs);
}

MeshRenderer::Uniforms MeshRenderer::find_uniforms(unsigned program) {
  const auto at = [program](const std::string& name) {
    return glGetUniformLocation(program, name.c_str());
  };
  Uniforms u;
  u.view_proj = at("u_view_proj");
  u.model = at("u_model");
  u.eye = at("u_eye");
  u.light0 = at("u_light0");
  u.light1 = at("u_light1");
  u.show_weights = at("u_show_weights");
  u.hand_mask = at("u_hand_mask");
  u.eps = at("u_eps");
  u.radius = at("u_radius");
  u.threshold = at("u_threshold");
  u.max_level = at("u_max_level");
  const char* names[] = {"u_axis", "u_mid", "u_chord", "u_axc", "u_shift"};
  for (std::size_t h = 0; h < 2; ++h) {
    const auto element = [h](const char* name) {
      return std::string(name) + "[" + std::to_string(h) + "]";
    };
    u.tint[h] = at(element("u_tint"));
    for (std::size_t k = 0; k < 5; ++k) u.hand_vec3[h][k] = at(element(names[k]));
    u.half[h] = at(element("u_half"));
    u.cot[h] = at(element("u_cot"));
    u.grab[h] = at(element("u_grab"));
  }
  return u;
}

void MeshRenderer::create_fbo(int width, int height) {
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glGenRenderbuffers(1, &color_rb_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_rb_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb_);
  glGenRenderbuffers(1, &depth_rb_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_rb_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb_);
}

hal::Expected<void> MeshRenderer::init(int width, int height, bool offscreen,
                                       const ViewConfig& view) {
  width_ = width;
  height_ = height;
  camera_.set_view(view);
  ShaderSources plain;
  plain.vertex = std::string(kGlsl330) + shaders::kWarpLibrary + shaders::kSurfaceStage +
                 shaders::kPlainVertex;
  plain.fragment = std::string(kGlsl330) + shaders::kMeshFragment;
  plain.feedback.assign(kFeedback.begin(), kFeedback.end());
  hal::Expected<unsigned> program = build_gl_program(plain);
  if (!program) return program.error();
  plain_ = {*program, find_uniforms(*program)};
  // The refined live preview needs tessellation (GL 4.0); without it the plain
  // program draws the live stroke too.
  if (epoxy_gl_version() >= 40) {
    ShaderSources refined;
    refined.vertex = std::string(kGlsl400) + shaders::kRefinedVertex;
    refined.tess_control = std::string(kGlsl400) + shaders::kWarpLibrary + shaders::kRefinedControl;
    refined.tess_evaluation = std::string(kGlsl400) + shaders::kWarpLibrary +
                              shaders::kSurfaceStage + shaders::kRefinedEvaluation;
    refined.fragment = std::string(kGlsl400) + shaders::kMeshFragment;
    refined.feedback.assign(kFeedback.begin(), kFeedback.end());
    hal::Expected<unsigned> tess = build_gl_program(refined);
    if (!tess) return tess.error();
    refined_ = {*tess, find_uniforms(*tess)};
    GLint max_level = 0;
    glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &max_level);
    max_level_ = static_cast<float>(std::clamp(max_level, 1, 64));
  }
  glGenVertexArrays(1, &vao_);
  glGenBuffers(static_cast<GLsizei>(vbo_.size()), vbo_.data());
  glGenBuffers(1, &ebo_);
  glGenBuffers(1, &live_ebo_);
  glBindVertexArray(vao_);
  const GLint sizes[] = {3, 2, 3, 3, 3, 2};
  for (GLuint a = 0; a < vbo_.size(); ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo_[a]);
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(a);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  ShaderSources symmetric;
  symmetric.vertex = std::string(kGlsl330) + shaders::kSurfaceStage + shaders::kSymmetricVertex;
  symmetric.fragment = plain.fragment;
  symmetric.feedback.assign(kFeedback.begin(), kFeedback.end());
  init_symmetric(symmetric);
  if (offscreen) {
    create_fbo(width, height);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      return hal::make_error(StatusCode::not_supported, "framebuffer object incomplete");
    }
  }
  glEnable(GL_DEPTH_TEST);
  return {};
}

void MeshRenderer::upload(unsigned buffer, const std::vector<float>& data,
                          std::size_t floats_per_vertex) {
  const std::size_t n = floats_per_vertex * vertex_count_;
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  if (data.size() >= n) {
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * sizeof(float)), data.data(),
                 GL_DYNAMIC_DRAW);
  } else {
    const std::vector<float> zero(n, 0.0F);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * sizeof(float)), zero.data(),
                 GL_DYNAMIC_DRAW);
  }
}

std::vector<float> MeshRenderer::drawn(const std::vector<float>& per_vertex,
                                       std::size_t columns) const {
  if (shaded_.identity()) return per_vertex;
  return to_drawn(shaded_, per_vertex, columns);
}

void MeshRenderer::set_mesh(const MeshData& mesh, bool keep_camera) {
  set_mesh(mesh, shade_with_creases(mesh, kDefaultCreaseAngleDeg), keep_camera);
}

void MeshRenderer::set_mesh(const MeshData& mesh, const ShadedMesh& shaded, bool keep_camera) {
  shaded_ = shaded;
  mesh_vertices_ = mesh.vertex_count();
  vertex_count_ = shaded.vertex_count();
  if (!keep_camera && mesh_vertices_ > 0) {
    glm::vec3 lo(1e30F);
    glm::vec3 hi(-1e30F);
    for (std::size_t i = 0; i < mesh_vertices_; ++i) {
      const glm::vec3 p(mesh.x[i], mesh.y[i], mesh.z[i]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    centre_ = 0.5F * (lo + hi);
    radius_ = std::max(0.5F * glm::length(hi - lo), 1e-6F);
    camera_.frame(glm::vec3(model_ * glm::vec4(centre_, 1.0F)), radius_);
  }
  glBindVertexArray(vao_);
  positions_ = interleaved_positions(mesh, shaded_);
  upload(vbo_[0], positions_, 3);
  upload(vbo_[1], {}, 2);
  upload(vbo_[2], shaded_.normals, 3);
  upload(vbo_[3], {}, 3);
  upload(vbo_[4], {}, 3);
  upload(vbo_[5], {}, 2);
  sym_version_ = 0;  // the spans are per vertex of the mesh: upload them again
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(shaded_.indices.size() * sizeof(std::uint32_t)),
               shaded_.indices.data(), GL_STATIC_DRAW);
  index_count_ = shaded_.indices.size();
  split_radius_ = -1.0F;
  positions_warped_ = false;
}

void MeshRenderer::set_positions(const MeshData& mesh) {
  positions_warped_ = true;
  positions_ = interleaved_positions(mesh, shaded_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(positions_.size() * sizeof(float)),
                  positions_.data());
  shade_normals(mesh, shaded_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[2]);
  glBufferSubData(GL_ARRAY_BUFFER, 0,
                  static_cast<GLsizeiptr>(shaded_.normals.size() * sizeof(float)),
                  shaded_.normals.data());
}

void MeshRenderer::set_weights(const std::vector<float>& w1, const std::vector<float>& w2,
                               std::array<std::uint8_t, 2> colour_hand) {
  colour_hand_ = colour_hand;
  std::vector<float> w(2 * mesh_vertices_, 0.0F);
  for (std::size_t i = 0; i < mesh_vertices_ && i < w1.size() && i < w2.size(); ++i) {
    w[2 * i] = w1[i];
    w[2 * i + 1] = w2[i];
  }
  upload(vbo_[1], drawn(w, 2), 2);
}

void MeshRenderer::set_gradients(const std::vector<float>& g1, const std::vector<float>& g2) {
  upload(vbo_[3], drawn(g1, 3), 3);
  upload(vbo_[4], drawn(g2, 3), 3);
}

void MeshRenderer::set_object_pose(const math::Frame& pose) {
  model_ = glm::mat4(glm::vec4(glm::vec3(pose.u), 0.0F), glm::vec4(glm::vec3(pose.v), 0.0F),
                     glm::vec4(glm::vec3(pose.w), 0.0F), glm::vec4(glm::vec3(pose.origin), 1.0F));
}

void MeshRenderer::set_live(const LiveState* live) {
  hand_mask_ = 0;
  cpu_live_ = false;
  sym_live_ = false;
  if (live == nullptr || !live->active) return;
  if (live->cpu_path()) {
    if (symmetric_fits(*live)) {  // a group: every image in the symmetric program
      set_symmetric(*live);
      sym_live_ = true;
      return;
    }
    cpu_live_ = true;  // scodef, or a group the GPU layout cannot take: positions uploaded
    return;
  }
  // Plan hands: hand k uses the k-th weight column.
  hand_mask_ = static_cast<int>((1u << live->hands.size()) - 1u);
  stroke_radius_ = static_cast<float>(live->radius_m);
  threshold_ = static_cast<float>(live->refine_threshold_m);
  // The kernels' per-hand constants, rounded to float for the shader uniforms.
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    float* k = hands_[h];
    std::fill(k, k + 17, 0.0F);
    if (h >= live->hands.size()) continue;
    math::KernelHand kh;
    const LiveHand& lh = live->hands[h];
    grab_[h] = glm::vec3(lh.start.origin);
    math::fill_kernel_hand(kh, lh.screw, lh.start, lh.end, live->method);
    const double* columns[] = {kh.axis, kh.mid, kh.chord, kh.axis_x_chord, kh.shift};
    for (std::size_t c = 0; c < 5; ++c) {
      for (std::size_t i = 0; i < 3; ++i) k[3 * c + i] = static_cast<float>(columns[c][i]);
    }
    k[15] = static_cast<float>(kh.half_angle);
    k[16] = static_cast<float>(kh.cot_half);
  }
}

void MeshRenderer::begin_frame() {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glClearColor(0.13F, 0.14F, 0.17F, 1.0F);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

bool MeshRenderer::refining_live() const {
  return refined_.id != 0 && allow_refinement_ && hand_mask_ != 0 && threshold_ > 0.0F;
}

void MeshRenderer::use(const Program& program) {
  const Uniforms& u = program.u;
  const glm::vec3 eye = camera_.eye();
  const glm::vec3 dir = camera_.direction();
  const glm::vec3 up = camera_.up();
  const glm::mat4 view_proj = camera_.projection(width_, height_) * camera_.view_matrix();
  glUseProgram(program.id);
  glUniformMatrix4fv(u.view_proj, 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniformMatrix4fv(u.model, 1, GL_FALSE, glm::value_ptr(model_));
  glUniform3fv(u.eye, 1, glm::value_ptr(eye));
  const glm::vec3 right = glm::normalize(glm::cross(-dir, up));
  const glm::vec3 l0 = glm::normalize(dir + 0.8F * up + 0.6F * right);
  const glm::vec3 l1 = glm::normalize(-dir + 0.3F * up - 0.8F * right);
  glUniform3fv(u.light0, 1, glm::value_ptr(l0));
  glUniform3fv(u.light1, 1, glm::value_ptr(l1));
  glUniform1i(u.show_weights, show_weights_ ? 1 : 0);
  glUniform1i(u.hand_mask, hand_mask_);
  if (&program == &symmetric_) bind_symmetric();
  glUniform1f(u.eps, 1e-3F * radius_);
  glUniform1f(u.radius, stroke_radius_);
  glUniform1f(u.threshold, threshold_);
  glUniform1f(u.max_level, max_level_);
  for (std::size_t h = 0; h < 2; ++h) {
    glUniform3fv(u.tint[h], 1, kHandColours[colour_hand_[h] & 1u].data());
    for (std::size_t k = 0; k < 5; ++k) glUniform3fv(u.hand_vec3[h][k], 1, &hands_[h][3 * k]);
    glUniform1f(u.half[h], hands_[h][15]);
    glUniform1f(u.cot[h], hands_[h][16]);
    glUniform3fv(u.grab[h], 1, glm::value_ptr(grab_[h]));
  }
  glBindVertexArray(vao_);
}

void MeshRenderer::split_live_triangles() {
  if (split_radius_ == stroke_radius_ && split_grab_ == grab_ && split_mask_ == hand_mask_) return;
  split_radius_ = stroke_radius_;
  split_grab_ = grab_;
  split_mask_ = hand_mask_;
  // A hand's weights vanish outside its ball (the squash only shrinks it): a triangle
  // whose bounding sphere meets no ball stays where it is, and its edges too.
  const auto at = [this](std::uint32_t v) {
    const std::size_t i = std::size_t{3} * v;
    return glm::vec3(positions_[i], positions_[i + 1], positions_[i + 2]);
  };
  std::vector<std::uint32_t> reached;
  std::vector<std::uint32_t> rest;
  reached.reserve(shaded_.indices.size());
  rest.reserve(shaded_.indices.size());
  for (std::size_t t = 0; t + 3 <= shaded_.indices.size(); t += 3) {
    const std::uint32_t* i = &shaded_.indices[t];
    const glm::vec3 a = at(i[0]), b = at(i[1]), c = at(i[2]);
    const glm::vec3 m = (a + b + c) / 3.0F;
    const float reach =
        stroke_radius_ + std::max({glm::length(a - m), glm::length(b - m), glm::length(c - m)});
    bool in = false;
    for (std::size_t h = 0; h < 2; ++h) {
      in = in || ((hand_mask_ & (1 << h)) != 0 && glm::length(m - grab_[h]) < reach);
    }
    (in ? reached : rest).insert((in ? reached : rest).end(), i, i + 3);
  }
  live_reached_ = reached.size();
  reached.insert(reached.end(), rest.begin(), rest.end());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, live_ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(reached.size() * sizeof(std::uint32_t)), reached.data(),
               GL_DYNAMIC_DRAW);
}

void MeshRenderer::draw_range(const Program& program, bool patches, std::size_t first,
                              std::size_t count) {
  if (count == 0) return;
  use(program);
  if (patches) glPatchParameteri(GL_PATCH_VERTICES, 3);
  glDrawElements(patches ? GL_PATCHES : GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));  // NOLINT
}

bool MeshRenderer::culling_faces() const {
  if (!allow_culling_ || shaded_.facing == Facing::both_sides || cpu_live_ || sym_live_ ||
      positions_warped_) {
    return false;
  }
  // The eye outside the model and the near plane clear of it: a closed surface's
  // hidden faces are then behind its visible ones. (The model matrix is rigid.)
  const glm::vec3 centre(model_ * glm::vec4(centre_, 1.0F));
  const float ahead = glm::dot(centre - camera_.eye(), -camera_.direction());
  return ahead - radius_ > camera_.near_distance();
}

void MeshRenderer::cull(Facing facing) {
  if (facing == Facing::both_sides) {
    glDisable(GL_CULL_FACE);
    return;
  }
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glCullFace(facing == Facing::front ? GL_BACK : GL_FRONT);
}

void MeshRenderer::draw_mesh() {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(vao_);
  const Facing rest = culling_faces() ? shaded_.facing : Facing::both_sides;
  if (!refining_live() && (hand_mask_ == 0 || rest == Facing::both_sides)) {
    cull(rest);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    draw_range(live_program(), false, 0, index_count_);
    cull(Facing::both_sides);
    return;
  }
  // What the balls can reach is warped (refined on GL 4), both faces drawn; the rest
  // is the mesh itself (the warp is the identity there, and so are the shared edges'
  // points on both sides), culled when the mesh allows.
  split_live_triangles();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, live_ebo_);
  cull(Facing::both_sides);
  draw_range(refining_live() ? refined_ : plain_, refining_live(), 0, live_reached_);
  cull(rest);
  draw_range(plain_, false, live_reached_, index_count_ - live_reached_);
  cull(Facing::both_sides);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
}

MeshRenderer::Surface MeshRenderer::capture_live_surface() {
  Surface out;
  const auto capture = [this, &out](const Program& program, bool patches, std::size_t first,
                                    std::size_t count) {
    if (count == 0) return;
    glEnable(GL_RASTERIZER_DISCARD);
    // First how many triangles the preview makes, then exactly that much room.
    GLuint query = 0;
    glGenQueries(1, &query);
    glBeginQuery(GL_PRIMITIVES_GENERATED, query);
    draw_range(program, patches, first, count);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    GLuint triangles = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &triangles);
    glDeleteQueries(1, &query);
    const std::size_t floats = std::size_t{triangles} * 3 * 6;  // rest, warped per corner
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffer);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(floats * sizeof(float)),
                 nullptr, GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
    glBeginTransformFeedback(GL_TRIANGLES);
    draw_range(program, patches, first, count);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    std::vector<float> data(floats);
    glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                       static_cast<GLsizeiptr>(floats * sizeof(float)), data.data());
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    glDeleteBuffers(1, &buffer);
    for (std::size_t i = 0; i + 6 <= floats; i += 6) {
      out.rest.emplace_back(data[i], data[i + 1], data[i + 2]);
      out.warped.emplace_back(data[i + 3], data[i + 4], data[i + 5]);
    }
  };
  glBindVertexArray(vao_);
  if (!refining_live()) {
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    capture(live_program(), false, 0, index_count_);
    return out;
  }
  split_live_triangles();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, live_ebo_);
  capture(refined_, true, 0, live_reached_);
  capture(plain_, false, live_reached_, index_count_ - live_reached_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  return out;
}

void MeshRenderer::end_frame() { glFinish(); }

void MeshRenderer::draw() {
  begin_frame();
  draw_mesh();
  end_frame();
}

std::vector<std::uint8_t> MeshRenderer::read_rgba() const {
  std::vector<std::uint8_t> rows(static_cast<std::size_t>(width_) *
                                 static_cast<std::size_t>(height_) * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  // GL's origin is bottom-left; images go top to bottom.
  const std::size_t stride = static_cast<std::size_t>(width_) * 4;
  for (std::size_t y = 0; y < static_cast<std::size_t>(height_) / 2; ++y) {
    std::swap_ranges(rows.begin() + static_cast<std::ptrdiff_t>(y * stride),
                     rows.begin() + static_cast<std::ptrdiff_t>((y + 1) * stride),
                     rows.begin() + static_cast<std::ptrdiff_t>(
                                        (static_cast<std::size_t>(height_) - 1 - y) * stride));
  }
  return rows;
}

}  // namespace twister::bridge
