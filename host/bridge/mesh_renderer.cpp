#include "mesh_renderer.hpp"

#include <epoxy/gl.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "twister/link/math_conversion.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::bridge {
namespace {

// The displacement is core's scalar kernel term by term (warp_kernels_scalar.cpp),
// so the preview equals the CPU warp up to float rounding.
constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec2 a_weight;
uniform mat4 u_mvp;
uniform int u_hand_mask;
uniform vec3 u_axis[2];
uniform vec3 u_mid[2];
uniform vec3 u_chord[2];
uniform vec3 u_axc[2];
uniform vec3 u_shift[2];
uniform float u_half[2];
uniform float u_cot[2];
out vec3 v_pos;
out vec2 v_weight;
vec3 displacement(int h, vec3 p, float t) {
  vec3 d = u_axis[h];
  vec3 v = p - u_mid[h];
  float hl = t * u_half[h];
  float sh = sin(hl);
  float ch = cos(hl);
  float a = sh * ch;
  float b = sh * sh;
  float k = u_cot[h];
  float dv = dot(d, v);
  vec3 c = cross(d, v);
  return a * (2.0 * c + k * u_chord[h]) + b * (2.0 * (d * dv - v) + k * u_axc[h]) +
         t * u_shift[h];
}
void main() {
  vec3 p = a_pos;
  vec3 q = p;
  if ((u_hand_mask & 1) != 0 && a_weight.x > 0.0) q += displacement(0, p, a_weight.x);
  if ((u_hand_mask & 2) != 0 && a_weight.y > 0.0) q += displacement(1, p, a_weight.y);
  v_pos = q;
  v_weight = a_weight;
  gl_Position = u_mvp * vec4(q, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_pos;
in vec2 v_weight;
uniform vec3 u_eye;
uniform vec3 u_light0;
uniform vec3 u_light1;
uniform int u_show_weights;
out vec4 frag;
void main() {
  vec3 n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  vec3 to_eye = normalize(u_eye - v_pos);
  if (dot(n, to_eye) < 0.0) n = -n;
  vec3 base = vec3(0.78, 0.80, 0.86);
  if (u_show_weights != 0) {
    base = mix(base, vec3(0.90, 0.12, 0.10), clamp(v_weight.x, 0.0, 1.0));
    base = mix(base, vec3(0.12, 0.80, 0.20), clamp(v_weight.y, 0.0, 1.0));
  }
  float d0 = max(dot(n, u_light0), 0.0);
  float d1 = max(dot(n, u_light1), 0.0);
  vec3 h = normalize(u_light0 + to_eye);
  float spec = pow(max(dot(n, h), 0.0), 40.0);
  vec3 c = base * (0.22 + 0.70 * d0 + 0.25 * d1) + vec3(0.25) * spec;
  frag = vec4(pow(c, vec3(1.0 / 1.1)), 1.0);
}
)";

// A compiled shader, or the driver's log.
hal::Expected<GLuint> compile(GLenum type, const char* source) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok == 0) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    return hal::make_error(StatusCode::not_supported, std::string("shader: ") + log);
  }
  return s;
}

// The linked program of both shaders.
hal::Expected<GLuint> build_program() {
  hal::Expected<GLuint> vs = compile(GL_VERTEX_SHADER, kVertexShader);
  if (!vs) return vs.error();
  hal::Expected<GLuint> fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  if (!fs) {
    glDeleteShader(*vs);
    return fs.error();
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, *vs);
  glAttachShader(program, *fs);
  glLinkProgram(program);
  glDeleteShader(*vs);
  glDeleteShader(*fs);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (linked == 0) {
    glDeleteProgram(program);
    return hal::make_error(StatusCode::not_supported, "shader program does not link");
  }
  return program;
}

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
  const GLuint buffers[] = {vbo_pos_, vbo_weight_, ebo_};
  glDeleteBuffers(3, buffers);
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  if (fbo_ != 0) glDeleteFramebuffers(1, &fbo_);
  const GLuint rbs[] = {color_rb_, depth_rb_};
  glDeleteRenderbuffers(2, rbs);
}

hal::Expected<void> MeshRenderer::init(int width, int height, bool offscreen,
                                       const ViewConfig& view) {
  width_ = width;
  height_ = height;
  view_ = view;
  hal::Expected<GLuint> program = build_program();
  if (!program) return program.error();
  program_ = *program;
  const auto at = [this](const std::string& name) {
    return glGetUniformLocation(program_, name.c_str());
  };
  uniforms_.mvp = at("u_mvp");
  uniforms_.eye = at("u_eye");
  uniforms_.light0 = at("u_light0");
  uniforms_.light1 = at("u_light1");
  uniforms_.show_weights = at("u_show_weights");
  uniforms_.hand_mask = at("u_hand_mask");
  const char* names[] = {"u_axis", "u_mid", "u_chord", "u_axc", "u_shift"};
  for (std::size_t h = 0; h < 2; ++h) {
    const auto element = [h](const char* name) {
      return std::string(name) + "[" + std::to_string(h) + "]";
    };
    for (std::size_t k = 0; k < 5; ++k) uniforms_.hand_vec3[h][k] = at(element(names[k]));
    uniforms_.half[h] = at(element("u_half"));
    uniforms_.cot[h] = at(element("u_cot"));
  }
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_pos_);
  glGenBuffers(1, &vbo_weight_);
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_weight_);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(1);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  if (offscreen) {
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
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      return hal::make_error(StatusCode::not_supported, "framebuffer object incomplete");
    }
  }
  glEnable(GL_DEPTH_TEST);
  return {};
}

void MeshRenderer::set_mesh(const MeshData& mesh, bool keep_camera) {
  vertex_count_ = mesh.vertex_count();
  if (!keep_camera && vertex_count_ > 0) {
    glm::vec3 lo(1e30F);
    glm::vec3 hi(-1e30F);
    for (std::size_t i = 0; i < vertex_count_; ++i) {
      const glm::vec3 p(mesh.x[i], mesh.y[i], mesh.z[i]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const glm::vec3 c = 0.5F * (lo + hi);
    center_[0] = c.x;
    center_[1] = c.y;
    center_[2] = c.z;
    radius_ = std::max(0.5F * glm::length(hi - lo), 1e-6F);
  }
  const std::vector<float> pos = interleaved_positions(mesh);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(pos.size() * sizeof(float)), pos.data(),
               GL_DYNAMIC_DRAW);
  std::vector<float> zero(2 * vertex_count_, 0.0F);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_weight_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(zero.size() * sizeof(float)), zero.data(),
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
  index_count_ = mesh.indices.size();
}

void MeshRenderer::set_positions(const MeshData& mesh) {
  const std::vector<float> pos = interleaved_positions(mesh);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(pos.size() * sizeof(float)),
                  pos.data());
}

void MeshRenderer::set_weights(const std::vector<float>& w1, const std::vector<float>& w2) {
  std::vector<float> w(2 * vertex_count_, 0.0F);
  for (std::size_t i = 0; i < vertex_count_ && i < w1.size() && i < w2.size(); ++i) {
    w[2 * i] = w1[i];
    w[2 * i + 1] = w2[i];
  }
  glBindBuffer(GL_ARRAY_BUFFER, vbo_weight_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(w.size() * sizeof(float)), w.data(),
               GL_DYNAMIC_DRAW);
}

void MeshRenderer::set_live(const LiveState* live) {
  hand_mask_ = 0;
  if (live == nullptr || !live->active) return;
  if (live->method == math::WarpMethod::scodef) return;  // CPU path (positions uploaded)
  // Plan hands: hand k uses the k-th weight column (red for the first, green for the second).
  hand_mask_ = static_cast<int>((1u << live->hand_count) - 1u);
  // The kernels' per-hand constants, rounded to float for the shader uniforms.
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    float* k = hands_[h];
    std::fill(k, k + 17, 0.0F);
    if (h >= live->hand_count) continue;
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

void MeshRenderer::draw() {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glClearColor(0.13F, 0.14F, 0.17F, 1.0F);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const glm::vec3 up(view_.up[0], view_.up[1], view_.up[2]);
  // A horizontal reference perpendicular to up, then azimuth/elevation about it.
  glm::vec3 side = glm::normalize(
      glm::cross(up, std::abs(up.x) < 0.9F ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 fwd = glm::cross(side, up);
  const float az = glm::radians(view_.azimuth_deg);
  const float el = glm::radians(view_.elevation_deg);
  const glm::vec3 dir =
      std::cos(el) * (std::cos(az) * fwd + std::sin(az) * side) + std::sin(el) * up;
  const glm::vec3 center(center_[0], center_[1], center_[2]);
  const float fov = glm::radians(35.0F);
  const float distance = 1.1F * view_.zoom_out * radius_ / std::sin(0.5F * fov);
  const glm::vec3 eye = center + distance * dir;
  const glm::mat4 proj =
      glm::perspective(fov, static_cast<float>(width_) / static_cast<float>(std::max(height_, 1)),
                       0.05F * distance, 4.0F * distance);
  const glm::mat4 mvp = proj * glm::lookAt(eye, center, up);
  glUseProgram(program_);
  glUniformMatrix4fv(uniforms_.mvp, 1, GL_FALSE, glm::value_ptr(mvp));
  glUniform3fv(uniforms_.eye, 1, glm::value_ptr(eye));
  const glm::vec3 right = glm::normalize(glm::cross(-dir, up));
  const glm::vec3 l0 = glm::normalize(dir + 0.8F * up + 0.6F * right);
  const glm::vec3 l1 = glm::normalize(-dir + 0.3F * up - 0.8F * right);
  glUniform3fv(uniforms_.light0, 1, glm::value_ptr(l0));
  glUniform3fv(uniforms_.light1, 1, glm::value_ptr(l1));
  glUniform1i(uniforms_.show_weights, hand_mask_ != 0 || show_weights_);
  glUniform1i(uniforms_.hand_mask, hand_mask_);
  for (std::size_t h = 0; h < 2; ++h) {
    for (std::size_t k = 0; k < 5; ++k) {
      glUniform3fv(uniforms_.hand_vec3[h][k], 1, &hands_[h][3 * k]);
    }
    glUniform1f(uniforms_.half[h], hands_[h][15]);
    glUniform1f(uniforms_.cot[h], hands_[h][16]);
  }
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr);
  glFinish();
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

hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return hal::make_error(StatusCode::io_error, "cannot write " + path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (png == nullptr || info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return hal::make_error(StatusCode::io_error, "cannot write " + path + " (libpng)");
  }
  png_init_io(png, f);
  png_set_compression_level(png, 1);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    png_write_row(png,
                  rgba.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 4);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) return hal::make_error(StatusCode::io_error, "cannot write " + path);
  return {};
}

}  // namespace twister::bridge
