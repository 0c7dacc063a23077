// A linked OpenGL program from its shaders' sources. Error not_supported with the
// driver's log when a shader does not compile or the program does not link. Needs a
// current context.
#pragma once

#include <string>
#include <vector>

#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Each stage's source; an empty string leaves the stage out (tessellation).
struct ShaderSources {
  std::string vertex;
  std::string tess_control;
  std::string tess_evaluation;
  std::string fragment;
  // Outputs of the last vertex stage captured by transform feedback (interleaved).
  std::vector<const char*> feedback;
};

hal::Expected<unsigned> build_gl_program(const ShaderSources& sources);

// Vertex and fragment shader only (GLSL 3.30 core).
hal::Expected<unsigned> build_gl_program(const char* vertex_source, const char* fragment_source);

}  // namespace twister::bridge
