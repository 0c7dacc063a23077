#include "window_input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>

namespace twister::bridge {
namespace {

constexpr float kOrbitDegPerPixel = 0.3F;
constexpr float kOrbitKeyDeg = 5.0F;
constexpr float kZoomStep = 1.1F;

WindowInput* self(GLFWwindow* w) { return static_cast<WindowInput*>(glfwGetWindowUserPointer(w)); }

}  // namespace

KeyAction key_action(int key) {
  switch (key) {
    case GLFW_KEY_LEFT:
      return KeyAction::orbit_left;
    case GLFW_KEY_RIGHT:
      return KeyAction::orbit_right;
    case GLFW_KEY_UP:
      return KeyAction::orbit_up;
    case GLFW_KEY_DOWN:
      return KeyAction::orbit_down;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
      return KeyAction::zoom_in;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
      return KeyAction::zoom_out;
    case GLFW_KEY_F:
    case GLFW_KEY_HOME:
      return KeyAction::reset_camera;
    case GLFW_KEY_H:
      return KeyAction::toggle_hud;
    case GLFW_KEY_C:
      return KeyAction::toggle_cues;
    case GLFW_KEY_Z:
      return KeyAction::undo;
    case GLFW_KEY_Y:
      return KeyAction::redo;
    case GLFW_KEY_M:
      return KeyAction::next_method;
    case GLFW_KEY_TAB:
      return KeyAction::toggle_audience;
    case GLFW_KEY_N:
      return KeyAction::new_sculpture;
    case GLFW_KEY_U:
      return KeyAction::undo_new_sculpture;
    case GLFW_KEY_S:
      return KeyAction::cycle_symmetry;
    default:
      return KeyAction::none;
  }
}

bool WindowInput::apply(KeyAction action) {
  Camera& camera = view_.renderer().camera();
  const bool camera_action = action >= KeyAction::orbit_left && action <= KeyAction::reset_camera;
  if (camera_action && fixed_) return false;
  switch (action) {
    case KeyAction::none:
      return false;
    case KeyAction::orbit_left:
    case KeyAction::orbit_right:
      camera.orbit(action == KeyAction::orbit_left ? -kOrbitKeyDeg : kOrbitKeyDeg, 0.0F);
      return true;
    case KeyAction::orbit_up:
    case KeyAction::orbit_down:
      camera.orbit(0.0F, action == KeyAction::orbit_up ? kOrbitKeyDeg : -kOrbitKeyDeg);
      return true;
    case KeyAction::zoom_in:
    case KeyAction::zoom_out:
      camera.zoom(action == KeyAction::zoom_in ? kZoomStep : 1.0F / kZoomStep);
      return true;
    case KeyAction::reset_camera:
      camera.reset();
      return true;
    case KeyAction::toggle_hud:
      view_.options().hud = !view_.options().hud;
      return true;
    case KeyAction::toggle_cues: {
      CueOptions& c = view_.options().cues;
      const bool on = !c.glyphs;
      c = CueOptions{on, on, on, on, on};
      return true;
    }
    case KeyAction::toggle_audience:
      view_.options().audience = view_.options().audience == Audience::visitor
                                     ? Audience::operator_hud
                                     : Audience::visitor;
      return true;
    case KeyAction::undo:
      return command({link::CommandKind::undo, 0});
    case KeyAction::redo:
      return command({link::CommandKind::redo, 0});
    case KeyAction::next_method:
      return command({link::CommandKind::next_method, 0});
    case KeyAction::new_sculpture:
      return command({link::CommandKind::new_sculpture, 0});
    case KeyAction::undo_new_sculpture: {
      const SceneReplica& r = app_.replica();
      if (app_.ready() && r.has_visitor() &&
          (r.visitor().flags & link::kVisitorResetUndoable) == 0) {
        view_.local_notice("Nothing to bring back: no sculpture was just ended");
        return false;
      }
      return command({link::CommandKind::undo_new_sculpture, 0});
    }
    case KeyAction::cycle_symmetry:
      return command({link::CommandKind::cycle_symmetry, 0});
  }
  return false;
}

bool WindowInput::command(const link::Command& c) {
  if (app_.spectator()) {
    view_.local_notice("This screen only watches: commands come from the sculpting station");
    return false;
  }
  if (!app_.send_command(c)) {
    view_.local_notice("Not connected to the station: the key did nothing");
    return false;
  }
  return true;
}

const char* key_help() {
  return "Keys (window and kiosk):\n"
         "  left drag, arrows   orbit the camera (not with a fixed camera)\n"
         "  right/middle drag   pan;  wheel, + / -  zoom;  F or Home  frame the model again\n"
         "  H                   show or hide the text on screen\n"
         "  Tab                 switch the text: the visitor's words or the operator's HUD\n"
         "  C                   show or hide the cues (hand glyphs, spheres, axes)\n"
         "  Z                   undo the last stroke (sent to the station)\n"
         "  Y                   redo\n"
         "  M                   next warp method\n"
         "  S                   next symmetry group (the station's [sculpt] symmetry_cycle)\n"
         "  N                   new sculpture: the station archives this one and starts over\n"
         "  U                   undo the new sculpture (while the station's grace time is open)\n"
         "A command key that does nothing (no link, a --spectator display, U too late) says why "
         "on screen.";
}

void WindowInput::mouse_button(int button, bool pressed, double x, double y) {
  last_x_ = x;
  last_y_ = y;
  if (button == GLFW_MOUSE_BUTTON_LEFT) orbiting_ = pressed && !fixed_;
  if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE) {
    panning_ = pressed && !fixed_;
  }
}

void WindowInput::cursor(double x, double y) {
  const auto dx = static_cast<float>(x - last_x_);
  const auto dy = static_cast<float>(y - last_y_);
  last_x_ = x;
  last_y_ = y;
  Camera& camera = view_.renderer().camera();
  if (orbiting_) camera.orbit(-kOrbitDegPerPixel * dx, kOrbitDegPerPixel * dy);
  if (panning_) {
    const auto h = static_cast<float>(std::max(view_.renderer().height(), 1));
    camera.pan(-dx / h, dy / h);
  }
}

void WindowInput::scroll(double dy) {
  if (!fixed_) view_.renderer().camera().zoom(std::pow(kZoomStep, static_cast<float>(dy)));
}

void WindowInput::attach(GLFWwindow* window) {
  if (window == nullptr) return;
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT) (void)self(w)->apply(key_action(key));
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(w, &x, &y);
    self(w)->mouse_button(button, action == GLFW_PRESS, x, y);
  });
  glfwSetCursorPosCallback(window,
                           [](GLFWwindow* w, double x, double y) { self(w)->cursor(x, y); });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) { self(w)->scroll(dy); });
}

}  // namespace twister::bridge
