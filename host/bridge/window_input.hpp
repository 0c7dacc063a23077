// WindowInput: the window's mouse and keys (GLFW callbacks).
//   mouse: left drag orbits, right or middle drag pans, the wheel zooms;
//   keys:  arrows orbit, + / - zoom, F or Home frames the model again (the view's
//          defaults), H shows or hides the heads-up text, C the cues;
//          Z undo, Y redo, M next warp method, S next symmetry group (the
//          station's [sculpt] symmetry_cycle): sent to the station as link
//          commands (BridgeApp::send_command), which it takes only from the
//          admitted display and runs through the session's command path.
// With a fixed camera (a kiosk's camera file) the mouse and the camera keys do
// nothing; the command keys still work.
#pragma once

#include <cstdint>

#include "bridge_app.hpp"
#include "scene_view.hpp"

struct GLFWwindow;

namespace twister::bridge {

enum class KeyAction : std::uint8_t {
  none,
  orbit_left,
  orbit_right,
  orbit_up,
  orbit_down,
  zoom_in,
  zoom_out,
  reset_camera,
  toggle_hud,
  toggle_cues,
  undo,
  redo,
  next_method,
  cycle_symmetry,
};

// The action of a GLFW key code (GLFW_KEY_*) pressed or repeated.
KeyAction key_action(int glfw_key);

class WindowInput {
 public:
  WindowInput(BridgeApp& app, SceneView& view, bool fixed_camera)
      : app_(app), view_(view), fixed_(fixed_camera) {}
  // Installs the callbacks on `window` (its user pointer becomes this object).
  void attach(GLFWwindow* window);
  // Carries out an action (also what the key callback does); false when ignored
  // (a camera action with a fixed camera, a command while the link is not ready).
  bool apply(KeyAction action);
  void mouse_button(int button, bool pressed, double x, double y);
  void cursor(double x, double y);
  void scroll(double dy);

 private:
  BridgeApp& app_;
  SceneView& view_;
  bool fixed_;
  bool orbiting_ = false;
  bool panning_ = false;
  double last_x_ = 0.0;
  double last_y_ = 0.0;
};

}  // namespace twister::bridge
