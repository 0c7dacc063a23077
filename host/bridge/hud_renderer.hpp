// HudRenderer: draws a HudText (hud_model.hpp) with Dear ImGui's OpenGL 3 back end
// over the current framebuffer: the lines in a translucent panel at the top-left
// corner, the banner large across the middle (the model stays visible around it).
// The display size is given per frame, so the same code serves the window, kiosk
// and offscreen (EGL) modes; the HUD takes no input (the window's mouse and keys
// are the camera's). Text in DejaVu Sans when the font is installed (ImGui's
// built-in font otherwise). One per process (ImGui keeps a current context).
#pragma once

#include <array>
#include <cstddef>

#include "hud_model.hpp"
#include "twister/hal/expected.hpp"

struct ImGuiContext;
struct ImFont;

namespace twister::bridge {

class HudRenderer {
 public:
  HudRenderer() = default;
  ~HudRenderer();
  HudRenderer(const HudRenderer&) = delete;
  HudRenderer& operator=(const HudRenderer&) = delete;
  // `height` picks the text size. Error not_supported: the ImGui OpenGL 3 back end
  // did not start.
  hal::Expected<void> init(int height);
  void draw(const HudText& text, int width, int height, double delta_s);
  // The panel's last drawn rectangle (pixels, top-left origin): x, y, w, h.
  const float* panel() const { return panel_; }

 private:
  void build(const HudText& text);

  ImGuiContext* context_ = nullptr;
  ImFont* text_font_ = nullptr;
  ImFont* banner_font_ = nullptr;
  bool backend_ = false;
  float panel_[4] = {0, 0, 0, 0};
  std::array<std::size_t, 6> layout_{};  // the text's shape when last laid out
};

}  // namespace twister::bridge
