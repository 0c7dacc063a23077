#include "cue_renderer.hpp"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include "gl_program.hpp"

namespace twister::bridge {
namespace {

constexpr const char* kVertex = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec4 a_colour;
uniform mat4 u_view_proj;
out vec4 v_colour;
void main() {
  v_colour = a_colour;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

constexpr const char* kFragment = R"(#version 330 core
in vec4 v_colour;
uniform float u_alpha;
out vec4 frag;
void main() { frag = vec4(v_colour.rgb, v_colour.a * u_alpha); }
)";

// How much of a cue hidden behind the model still shows.
constexpr float kHiddenAlpha = 0.35F;

}  // namespace

CueRenderer::~CueRenderer() {
  if (program_ != 0) glDeleteProgram(program_);
  if (vao_ != 0) {
    const GLuint buffers[] = {vbo_pos_, vbo_colour_, ebo_};
    glDeleteBuffers(3, buffers);
    glDeleteVertexArrays(1, &vao_);
  }
}

hal::Expected<void> CueRenderer::init() {
  hal::Expected<unsigned> program = build_gl_program(kVertex, kFragment);
  if (!program) return program.error();
  program_ = *program;
  u_view_proj_ = glGetUniformLocation(program_, "u_view_proj");
  u_alpha_ = glGetUniformLocation(program_, "u_alpha");
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_pos_);
  glGenBuffers(1, &vbo_colour_);
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_colour_);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(1);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  return {};
}

void CueRenderer::draw_mesh(const CueMesh& mesh, float alpha_scale) {
  if (mesh.indices.empty()) return;
  glUniform1f(u_alpha_, alpha_scale);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_pos_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(float)),
               mesh.positions.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_colour_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.colours.size() * sizeof(float)),
               mesh.colours.data(), GL_STREAM_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STREAM_DRAW);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
}

void CueRenderer::draw(const CueScene& scene, const glm::mat4& view_proj) {
  glUseProgram(program_);
  glUniformMatrix4fv(u_view_proj_, 1, GL_FALSE, glm::value_ptr(view_proj));
  glBindVertexArray(vao_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  // Hidden parts first (behind the model: faded), then the visible ones, solid.
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GREATER);
  draw_mesh(scene.lines, kHiddenAlpha);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  draw_mesh(scene.lines, 1.0F);
  // Translucent balls: front faces only, no depth write (the model shows through).
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  draw_mesh(scene.translucent, 1.0F);
  glDisable(GL_CULL_FACE);
  // Cursors on top.
  glDisable(GL_DEPTH_TEST);
  draw_mesh(scene.overlay, 1.0F);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

}  // namespace twister::bridge
