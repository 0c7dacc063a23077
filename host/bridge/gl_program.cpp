#include "gl_program.hpp"

#include <epoxy/gl.h>

#include <string>

namespace twister::bridge {
namespace {

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

}  // namespace

hal::Expected<unsigned> build_gl_program(const char* vertex_source, const char* fragment_source) {
  hal::Expected<GLuint> vs = compile(GL_VERTEX_SHADER, vertex_source);
  if (!vs) return vs.error();
  hal::Expected<GLuint> fs = compile(GL_FRAGMENT_SHADER, fragment_source);
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

}  // namespace twister::bridge
