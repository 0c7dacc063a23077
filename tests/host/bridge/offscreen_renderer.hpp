// The bridge's picture tests' OpenGL: an offscreen context (EGL surfaceless + FBO,
// Mesa llvmpipe) and a MeshRenderer in it. Headless on purpose: never a display
// server, even when one is around.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "gl_context.hpp"
#include "mesh_renderer.hpp"

namespace twister::bridge::test {

inline ::testing::AssertionResult open_offscreen(std::unique_ptr<GlContext>& context,
                                                 MeshRenderer& renderer, int width, int height,
                                                 const ViewConfig& view = {}) {
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  auto made = make_offscreen_context(width, height);
  if (!made) return ::testing::AssertionFailure() << made.error().message;
  context = std::move(*made);
  if (const hal::Expected<void> ready = renderer.init(width, height, true, view); !ready) {
    return ::testing::AssertionFailure() << ready.error().message;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace twister::bridge::test
