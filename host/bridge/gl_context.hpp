// OpenGL 3.3 core contexts for the bridge: EGL surfaceless (offscreen, no display
// server; Mesa llvmpipe in CI) or a GLFW window (desk display or kiosk full screen).
// Functions are loaded through libepoxy. Both throw nothing: a failure is an Error
// (status unavailable: no display / driver; message for the log).
#pragma once

#include <memory>

#include "twister/hal/expected.hpp"

struct GLFWwindow;

namespace twister::bridge {

class GlContext {
 public:
  virtual ~GlContext() = default;
  // Presents the frame (window) or nothing (offscreen).
  virtual void swap() {}
  // false when the user closed the window.
  virtual bool open() const { return true; }
  virtual void poll_events() {}
  // Drawable size in pixels.
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual bool offscreen() const = 0;
  // The GLFW window (input callbacks); null offscreen.
  virtual GLFWwindow* window() { return nullptr; }
};

// Surfaceless EGL + a current context (draw into an FBO).
hal::Expected<std::unique_ptr<GlContext>> make_offscreen_context(int width, int height);
// A window (full screen on the primary monitor when kiosk).
hal::Expected<std::unique_ptr<GlContext>> make_window_context(int width, int height, bool kiosk);

}  // namespace twister::bridge
