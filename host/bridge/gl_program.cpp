#include "gl_program.hpp"

#include <epoxy/gl.h>

#include <array>
#include <utility>

namespace twister::bridge {
namespace {

// A compiled shader, or the driver's log.
hal::Expected<GLuint> compile(GLenum type, const std::string& source) {
  const GLuint s = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
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

}  // namespace

hal::Expected<unsigned> build_gl_program(const ShaderSources& sources) {
  const std::array<std::pair<GLenum, const std::string*>, 4> stages{{
      {GL_VERTEX_SHADER, &sources.vertex},
      {GL_TESS_CONTROL_SHADER, &sources.tess_control},
      {GL_TESS_EVALUATION_SHADER, &sources.tess_evaluation},
      {GL_FRAGMENT_SHADER, &sources.fragment},
  }};
  const GLuint program = glCreateProgram();
  std::array<GLuint, 4> shaders{};
  hal::Expected<void> compiled{};
  for (std::size_t i = 0; i < stages.size() && compiled; ++i) {
    if (stages[i].second->empty()) continue;
    hal::Expected<GLuint> s = compile(stages[i].first, *stages[i].second);
    if (!s) {
      compiled = s.error();
      break;
    }
    shaders[i] = *s;
    glAttachShader(program, *s);
  }
  if (compiled && !sources.feedback.empty()) {
    glTransformFeedbackVaryings(program, static_cast<GLsizei>(sources.feedback.size()),
                                sources.feedback.data(), GL_INTERLEAVED_ATTRIBS);
  }
  if (compiled) glLinkProgram(program);
  for (const GLuint s : shaders) {
    if (s != 0) glDeleteShader(s);
  }
  if (!compiled) {
    glDeleteProgram(program);
    return compiled.error();
  }
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (linked == 0) {
    char log[1024] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    return hal::make_error(StatusCode::not_supported,
                           std::string("shader program does not link: ") + log);
  }
  return program;
}

hal::Expected<unsigned> build_gl_program(const char* vertex_source, const char* fragment_source) {
  ShaderSources s;
  s.vertex = vertex_source;
  s.fragment = fragment_source;
  return build_gl_program(s);
}

}  // namespace twister::bridge
