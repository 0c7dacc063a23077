// HudRenderer: draws a HudText (hud_model.hpp) with Dear ImGui's OpenGL 3 back end
// over the current framebuffer: the lines in a translucent panel at the top-left
// corner, the banner large across the middle (the model stays visible around it);
// the exhibit's words (exhibit_model.hpp): notices in a strip at the top middle, the
// visitor's prompt large in the lower middle with its detail under it.
// The display size is given per frame, so the same code serves the window, kiosk
// and offscreen (EGL) modes; the HUD takes no input (the window's mouse and keys
// are the camera's). Text in DejaVu Sans when the font is installed (ImGui's
// built-in font otherwise). One per process (ImGui keeps a current context).
#pragma once

#include <array>
#include <cstddef>

#include "exhibit_model.hpp"
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
  void draw(const HudText& text, int width, int height, double delta_s,
            const ExhibitText& exhibit = {});
  // The panel's last drawn rectangle (pixels, top-left origin): x, y, w, h (all 0
  // when there were no lines); the prompt's and the notices' likewise.
  const float* panel() const { return panel_; }
  const float* prompt() const { return prompt_; }
  const float* notices() const { return notices_; }

 private:
  void build(const HudText& text, const ExhibitText& exhibit);
  void build_exhibit(const ExhibitText& exhibit);

  ImGuiContext* context_ = nullptr;
  ImFont* text_font_ = nullptr;
  ImFont* banner_font_ = nullptr;
  ImFont* prompt_font_ = nullptr;
  bool backend_ = false;
  float panel_[4] = {0, 0, 0, 0};
  float prompt_[4] = {0, 0, 0, 0};
  float notices_[4] = {0, 0, 0, 0};
  std::array<std::size_t, 9> layout_{};  // the text's shape when last laid out
};

}  // namespace twister::bridge
