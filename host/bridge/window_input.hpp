// WindowInput: the window's mouse and keys (GLFW callbacks).
//   mouse: left drag orbits, right or middle drag pans, the wheel zooms;
//   keys:  arrows orbit, + / - zoom, F or Home frames the model again (the view's
//          defaults), H shows or hides the heads-up text, C the cues;
//          Z undo, Y redo, M next warp method, S next symmetry group (the
//          station's [sculpt] symmetry_cycle): sent to the station as link
//          commands (BridgeApp::send_command), which it takes only from the
//          admitted display and runs through the session's command path;
//          N new sculpture (the station archives this one and starts over), U
//          brings it back while the station's grace time is open; Tab switches
//          the text between the visitor's words and the operator's HUD.
// A command key that does nothing here (no link yet, a spectator display, U with
// no grace open) says why on screen (SceneView::local_notice).
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
  toggle_audience,
  new_sculpture,
  undo_new_sculpture,
  cycle_symmetry,
};

// Every key, one line each, for twister-bridge --help.
const char* key_help();

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
  // Sends a command key's command, or says on screen why it was not sent.
  bool command(const link::Command& c);

  BridgeApp& app_;
  SceneView& view_;
  bool fixed_;
  bool orbiting_ = false;
  bool panning_ = false;
  double last_x_ = 0.0;
  double last_y_ = 0.0;
};

}  // namespace twister::bridge
