#include "mesh_renderer.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_program.hpp"
#include "mesh_shaders.hpp"
#include "twister/math/warp_plan.hpp"
#include "vertex_normals.hpp"

namespace twister::bridge {
namespace {

// x0 y0 z0 x1 y1 z1 ... for the position buffer.
std::vector<float> interleaved_positions(const MeshData& mesh) {
  std::vector<float> pos(3 * mesh.vertex_count());
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    pos[3 * i] = mesh.x[i];
    pos[3 * i + 1] = mesh.y[i];
    pos[3 * i + 2] = mesh.z[i];
  }
  return pos;
}

}  // namespace

MeshRenderer::~MeshRenderer() {
  if (program_ != 0) glDeleteProgram(program_);
  if (vao_ != 0) {
    glDeleteBuffers(static_cast<GLsizei>(vbo_.size()), vbo_.data());
    glDeleteBuffers(1, &ebo_);
    glDeleteVertexArrays(1, &vao_);
  }
  if (fbo_ != 0) glDeleteFramebuffers(1, &fbo_);
  const GLuint rbs[] = {color_rb_, depth_rb_};
  if (color_rb_ != 0) glDeleteRenderbuffers(2, rbs);
}

void MeshRenderer::find_uniforms() {
  const auto at = [this](const std::string& name) {
    return glGetUniformLocation(program_, name.c_str());
  };
  uniforms_.view_proj = at("u_view_proj");
  uniforms_.model = at("u_model");
  uniforms_.eye = at("u_eye");
  uniforms_.light0 = at("u_light0");
  uniforms_.light1 = at("u_light1");
  uniforms_.show_weights = at("u_show_weights");
  uniforms_.hand_mask = at("u_hand_mask");
  uniforms_.eps = at("u_eps");
  uniforms_.tint[0] = at("u_tint[0]");
  uniforms_.tint[1] = at("u_tint[1]");
  const char* names[] = {"u_axis", "u_mid", "u_chord", "u_axc", "u_shift"};
  for (std::size_t h = 0; h < 2; ++h) {
    const auto element = [h](const char* name) {
      return std::string(name) + "[" + std::to_string(h) + "]";
    };
    for (std::size_t k = 0; k < 5; ++k) uniforms_.hand_vec3[h][k] = at(element(names[k]));
    uniforms_.half[h] = at(element("u_half"));
    uniforms_.cot[h] = at(element("u_cot"));
  }
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
  hal::Expected<unsigned> program = build_gl_program(shaders::kMeshVertex, shaders::kMeshFragment);
  if (!program) return program.error();
  program_ = *program;
  find_uniforms();
  glGenVertexArrays(1, &vao_);
  glGenBuffers(static_cast<GLsizei>(vbo_.size()), vbo_.data());
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  const GLint sizes[] = {3, 2, 3, 3, 3};
  for (GLuint a = 0; a < vbo_.size(); ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo_[a]);
    glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, 0, nullptr);
    glEnableVertexAttribArray(a);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
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

void MeshRenderer::set_mesh(const MeshData& mesh, const std::vector<float>& normals,
                            bool keep_camera) {
  vertex_count_ = mesh.vertex_count();
  if (!keep_camera && vertex_count_ > 0) {
    glm::vec3 lo(1e30F);
    glm::vec3 hi(-1e30F);
    for (std::size_t i = 0; i < vertex_count_; ++i) {
      const glm::vec3 p(mesh.x[i], mesh.y[i], mesh.z[i]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    centre_ = 0.5F * (lo + hi);
    radius_ = std::max(0.5F * glm::length(hi - lo), 1e-6F);
    camera_.frame(glm::vec3(model_ * glm::vec4(centre_, 1.0F)), radius_);
  }
  glBindVertexArray(vao_);
  upload(vbo_[0], interleaved_positions(mesh), 3);
  upload(vbo_[1], {}, 2);
  if (normals.size() == 3 * vertex_count_) {
    upload(vbo_[2], normals, 3);
  } else {
    std::vector<float> computed;
    compute_vertex_normals(mesh, computed);
    upload(vbo_[2], computed, 3);
  }
  upload(vbo_[3], {}, 3);
  upload(vbo_[4], {}, 3);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
  index_count_ = mesh.indices.size();
}

void MeshRenderer::set_positions(const MeshData& mesh) {
  const std::vector<float> pos = interleaved_positions(mesh);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(pos.size() * sizeof(float)),
                  pos.data());
  std::vector<float> normals;
  compute_vertex_normals(mesh, normals);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[2]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(normals.size() * sizeof(float)),
                  normals.data());
}

void MeshRenderer::set_weights(const std::vector<float>& w1, const std::vector<float>& w2,
                               std::array<std::uint8_t, 2> colour_hand) {
  colour_hand_ = colour_hand;
  std::vector<float> w(2 * vertex_count_, 0.0F);
  for (std::size_t i = 0; i < vertex_count_ && i < w1.size() && i < w2.size(); ++i) {
    w[2 * i] = w1[i];
    w[2 * i + 1] = w2[i];
  }
  upload(vbo_[1], w, 2);
}

void MeshRenderer::set_gradients(const std::vector<float>& g1, const std::vector<float>& g2) {
  upload(vbo_[3], g1, 3);
  upload(vbo_[4], g2, 3);
}

void MeshRenderer::set_object_pose(const math::Frame& pose) {
  model_ = glm::mat4(glm::vec4(glm::vec3(pose.u), 0.0F), glm::vec4(glm::vec3(pose.v), 0.0F),
                     glm::vec4(glm::vec3(pose.w), 0.0F), glm::vec4(glm::vec3(pose.origin), 1.0F));
}

void MeshRenderer::set_live(const LiveState* live) {
  hand_mask_ = 0;
  if (live == nullptr || !live->active) return;
  if (live->method == math::WarpMethod::scodef) return;  // CPU path (positions uploaded)
  // Plan hands: hand k uses the k-th weight column.
  hand_mask_ = static_cast<int>((1u << live->hands.size()) - 1u);
  // The kernels' per-hand constants, rounded to float for the shader uniforms.
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    float* k = hands_[h];
    std::fill(k, k + 17, 0.0F);
    if (h >= live->hands.size()) continue;
    math::KernelHand kh;
    const LiveHand& lh = live->hands[h];
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

void MeshRenderer::draw_mesh() {
  const glm::vec3 eye = camera_.eye();
  const glm::vec3 dir = camera_.direction();
  const glm::vec3 up = camera_.up();
  const glm::mat4 view_proj = camera_.projection(width_, height_) * camera_.view_matrix();
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program_);
  glUniformMatrix4fv(uniforms_.view_proj, 1, GL_FALSE, glm::value_ptr(view_proj));
  glUniformMatrix4fv(uniforms_.model, 1, GL_FALSE, glm::value_ptr(model_));
  glUniform3fv(uniforms_.eye, 1, glm::value_ptr(eye));
  const glm::vec3 right = glm::normalize(glm::cross(-dir, up));
  const glm::vec3 l0 = glm::normalize(dir + 0.8F * up + 0.6F * right);
  const glm::vec3 l1 = glm::normalize(-dir + 0.3F * up - 0.8F * right);
  glUniform3fv(uniforms_.light0, 1, glm::value_ptr(l0));
  glUniform3fv(uniforms_.light1, 1, glm::value_ptr(l1));
  glUniform1i(uniforms_.show_weights, show_weights_ ? 1 : 0);
  glUniform1i(uniforms_.hand_mask, hand_mask_);
  glUniform1f(uniforms_.eps, 1e-3F * radius_);
  for (std::size_t c = 0; c < 2; ++c) {
    glUniform3fv(uniforms_.tint[c], 1, kHandColours[colour_hand_[c] & 1u].data());
  }
  for (std::size_t h = 0; h < 2; ++h) {
    for (std::size_t k = 0; k < 5; ++k) {
      glUniform3fv(uniforms_.hand_vec3[h][k], 1, &hands_[h][3 * k]);
    }
    glUniform1f(uniforms_.half[h], hands_[h][15]);
    glUniform1f(uniforms_.cot[h], hands_[h][16]);
  }
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
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
