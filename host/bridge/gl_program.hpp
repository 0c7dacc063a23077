// A linked OpenGL program from a vertex and a fragment shader's source (GLSL 3.30
// core). Error not_supported with the driver's log when either does not compile or
// the program does not link. Needs a current context.
#pragma once

#include "twister/hal/expected.hpp"

namespace twister::bridge {

hal::Expected<unsigned> build_gl_program(const char* vertex_source, const char* fragment_source);

}  // namespace twister::bridge
