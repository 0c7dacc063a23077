// EGL surfaceless is selected explicitly: without DISPLAY the default EGL display
// fails on Mesa, and eglGetPlatformDisplayEXT (not the 1.5 entry point) is what
// works through libepoxy (docs/bridge.md "Software GL").
#include "gl_context.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
// GLFW after epoxy: epoxy provides the GL declarations.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace twister::bridge {
namespace {

hal::Error unavailable(const char* message) {
  return hal::make_error(StatusCode::unavailable, message);
}

class OffscreenContext final : public GlContext {
 public:
  OffscreenContext(EGLDisplay display, EGLContext context, int w, int h)
      : display_(display), context_(context), width_(w), height_(h) {}
  ~OffscreenContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // No eglTerminate: it unloads Mesa's driver, whose few static allocations then
    // show up as leaks from an unknown module under LeakSanitizer; the process is
    // ending anyway and the display is process-wide.
    eglReleaseThread();
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  bool offscreen() const override { return true; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  int width_;
  int height_;
};

class WindowContext final : public GlContext {
 public:
  explicit WindowContext(GLFWwindow* window) : window_(window) {}
  ~WindowContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  void swap() override { glfwSwapBuffers(window_); }
  bool open() const override { return glfwWindowShouldClose(window_) == 0; }
  void poll_events() override { glfwPollEvents(); }
  int width() const override {
    int w = 0;
    int h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0;
    int h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
  }
  bool offscreen() const override { return false; }
  GLFWwindow* window() override { return window_; }

 private:
  GLFWwindow* window_;
};

}  // namespace

hal::Expected<std::unique_ptr<GlContext>> make_offscreen_context(int width, int height) {
  EGLDisplay display =
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) {
    return unavailable("EGL: no surfaceless display (Mesa EGL_MESA_platform_surfaceless missing)");
  }
  EGLint major = 0;
  EGLint minor = 0;
  if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
    return unavailable("EGL: eglInitialize failed");
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    eglTerminate(display);
    return unavailable("EGL: desktop OpenGL not available");
  }
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display, config_attribs, &config, 1, &count) != EGL_TRUE || count == 0) {
    config = nullptr;  // surfaceless needs no config (EGL_KHR_no_config_context)
  }
  // 4.1 core for the refined live preview (tessellation), else 3.3 core.
  EGLContext context = EGL_NO_CONTEXT;
  for (const EGLint version : {41, 33}) {
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      version / 10,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      version % 10,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context != EGL_NO_CONTEXT) break;
  }
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    return unavailable("EGL: cannot create an OpenGL 3.3 core context");
  }
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    return unavailable("EGL: eglMakeCurrent (surfaceless) failed");
  }
  return std::unique_ptr<GlContext>(
      std::make_unique<OffscreenContext>(display, context, width, height));
}

hal::Expected<std::unique_ptr<GlContext>> make_window_context(int width, int height, bool kiosk) {
  if (glfwInit() != GLFW_TRUE) {
    return unavailable("GLFW: cannot initialise (no display? use --offscreen)");
  }
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWmonitor* monitor = nullptr;
  if (kiosk) {
    monitor = glfwGetPrimaryMonitor();
    if (monitor != nullptr) {
      const GLFWvidmode* mode = glfwGetVideoMode(monitor);
      width = mode->width;
      height = mode->height;
    }
  }
  // 4.1 core for the refined live preview (tessellation), else 3.3 core.
  GLFWwindow* window = nullptr;
  for (const int version : {41, 33}) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, version / 10);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, version % 10);
    window = glfwCreateWindow(width, height, "Twister", monitor, nullptr);
    if (window != nullptr) break;
  }
  if (window == nullptr) {
    glfwTerminate();
    return unavailable("GLFW: cannot open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  return std::unique_ptr<GlContext>(std::make_unique<WindowContext>(window));
}

}  // namespace twister::bridge
