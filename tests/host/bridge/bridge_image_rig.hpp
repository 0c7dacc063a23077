// Test rig of the display's image tests: an OpenGL context (EGL surfaceless +
// FBO, or a GLFW window when TWISTER_TEST_DISPLAY=window, run under Xvfb), the
// renderer with cues and HUD (SceneView) behind a BridgeApp on a quiet link, a
// sphere loaded into its replica, and pixel helpers: project world points through
// the renderer's camera and classify the colours found there.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bridge_app.hpp"
#include "bridge_test_mesh.hpp"
#include "fakes/fake_clock.hpp"
#include "gl_context.hpp"
#include "scene_view.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge::test {

// RGBA rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  std::array<int, 3> at(int x, int y) const {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          4;
    return {rgba[i], rgba[i + 1], rgba[i + 2]};
  }
};

// Colour classes, loose enough for lit, blended and faded (hidden) cues.
inline bool is_red(std::array<int, 3> c) { return c[0] - c[1] > 60 && c[0] - c[2] > 60; }
inline bool is_green(std::array<int, 3> c) { return c[1] - c[0] > 50 && c[1] - c[2] > 40; }
inline bool is_pink(std::array<int, 3> c) { return c[0] - c[1] > 40 && c[2] - c[1] > 15; }
inline bool is_yellow(std::array<int, 3> c) { return c[0] - c[2] > 40 && c[1] - c[2] > 40; }
inline bool is_background(std::array<int, 3> c) {
  return std::abs(c[0] - 33) + std::abs(c[1] - 36) + std::abs(c[2] - 43) <= 3;
}

// True when a pixel within `r` of (x, y) satisfies `pred`.
template <typename Pred>
bool near(const Image& img, glm::vec2 p, int r, Pred pred) {
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (pred(img.at(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy))) return true;
    }
  }
  return false;
}

// Pixels satisfying `pred` in the box of half size `r` around p.
template <typename Pred>
int count_near(const Image& img, glm::vec2 p, int r, Pred pred) {
  int n = 0;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      n += pred(img.at(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy)) ? 1 : 0;
    }
  }
  return n;
}

// An empty or black frame fails: most pixels black, one colour only, or nothing
// but the clear colour.
inline void expect_live_frame(const Image& img) {
  std::set<std::uint32_t> colours;
  std::size_t black = 0;
  std::size_t background = 0;
  for (int y = 0; y < img.height; y += 2) {
    for (int x = 0; x < img.width; x += 2) {
      const auto c = img.at(x, y);
      black += c[0] + c[1] + c[2] < 24 ? 1 : 0;
      background += is_background(c) ? 1 : 0;
      colours.insert(static_cast<std::uint32_t>(c[0] << 16 | c[1] << 8 | c[2]));
    }
  }
  const std::size_t n =
      static_cast<std::size_t>(img.width / 2) * static_cast<std::size_t>(img.height / 2);
  EXPECT_LT(black, n / 2) << "frame mostly black";
  EXPECT_LT(background, n * 98 / 100) << "frame holds nothing but the background";
  EXPECT_GT(colours.size(), 50u) << "frame nearly uniform";
}

// A connected link with nothing to say: BridgeApp::step() only refreshes the display.
class QuietLink final : public ports::LinkPort {
  Result<std::size_t> do_send(std::span<const std::byte> src) override { return src.size(); }
  Result<std::size_t> do_receive(std::span<std::byte>) override { return std::size_t{0}; }
};

class DisplayRig : public ::testing::Test {
 public:
  const MeshRenderer& renderer() const { return renderer_; }

 protected:
  static constexpr int kW = 640;
  static constexpr int kH = 480;
  void SetUp() override {
    const char* mode = std::getenv("TWISTER_TEST_DISPLAY");
    window_ = mode != nullptr && std::string(mode) == "window";
    if (!window_) {
      ::unsetenv("DISPLAY");  // headless on purpose
      ::unsetenv("WAYLAND_DISPLAY");
    }
    auto context = window_ ? make_window_context(kW, kH, false) : make_offscreen_context(kW, kH);
    ASSERT_TRUE(context) << context.error().message;
    context_ = std::move(*context);
    const hal::Expected<void> ready =
        renderer_.init(context_->width(), context_->height(), !window_, ViewConfig{});
    ASSERT_TRUE(ready) << ready.error().message;
    view_ = std::make_unique<SceneView>(renderer_, clock_, options_);
    const hal::Expected<void> view = view_->init();
    ASSERT_TRUE(view) << view.error().message;
    app_ = std::make_unique<BridgeApp>(link_, clock_, &renderer_, BridgeOptions{}, log_);
    app_->set_view(view_.get());
  }
  // Steps the app (uploads), draws a frame and reads it back (before any swap).
  Image frame() {
    app_->step();
    app_->draw();
    Image img{renderer_.width(), renderer_.height(), renderer_.read_rgba()};
    if (window_) context_->swap();
    if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
      (void)write_png(std::string(dir) + "/" + name() + ".png", img.width, img.height, img.rgba);
    }
    return img;
  }
  std::string name() const {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return std::string(info->name()) + (window_ ? "_window" : "_offscreen") + "_" +
           std::to_string(++frames_);
  }
  std::optional<glm::vec2> project_object(glm::dvec3 p) const {
    const glm::vec3 world = glm::vec3(renderer_.model_matrix() * glm::vec4(glm::vec3(p), 1.0F));
    return renderer_.camera().project(world, renderer_.width(), renderer_.height());
  }

  bool window_ = false;
  SceneViewOptions options_{};
  std::unique_ptr<GlContext> context_;
  MeshRenderer renderer_;
  twister::test::FakeClock clock_;  // the HUD's and the link's time: still unless a test moves it
  std::unique_ptr<SceneView> view_;
  QuietLink link_;
  ports::NullLogSink log_;
  std::unique_ptr<BridgeApp> app_;
  mutable int frames_ = 0;
};

}  // namespace twister::bridge::test
