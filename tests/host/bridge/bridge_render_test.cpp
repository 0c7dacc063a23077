// Offscreen rendering on Mesa llvmpipe (EGL surfaceless + FBO): the model covers
// the centre, the live warp changes the picture where the stroke's weights are,
// and the shader's warp equals core's CPU warp drawn as plain geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "bridge_app.hpp"
#include "bridge_test_mesh.hpp"
#include "fakes/fake_clock.hpp"
#include "gl_context.hpp"
#include "mesh_renderer.hpp"
#include "offscreen_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/screw.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge {
namespace {

using test::differing;
using test::load_mesh;
using test::sphere_mesh;

constexpr int kW = 320;
constexpr int kH = 240;
// The clear colour (0.13, 0.14, 0.17) in 8 bits.
constexpr std::array<int, 3> kBackground{33, 36, 43};

// Fraction of pixels that are background (the clear colour) in one picture only.
double coverage_differs(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  const auto background = [](const std::uint8_t* p) {
    return std::abs(int{p[0]} - int{kBackground[0]}) + std::abs(int{p[1]} - int{kBackground[1]}) +
               std::abs(int{p[2]} - int{kBackground[2]}) <=
           3;
  };
  std::size_t n = 0;
  for (std::size_t p = 0; p < a.size(); p += 4) n += background(&a[p]) != background(&b[p]);
  return static_cast<double>(n) / static_cast<double>(a.size() / 4);
}

class BridgeRender : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(test::open_offscreen(context_, renderer_, kW, kH)); }
  std::unique_ptr<GlContext> context_;
  MeshRenderer renderer_;
};

TEST_F(BridgeRender, LiveWarpInTheShaderEqualsTheCpuWarp) {
  SceneReplica r;
  load_mesh(r, sphere_mesh(0.1F));
  renderer_.set_mesh(r.mesh(), false);
  renderer_.draw();
  const auto rest = renderer_.read_rgba();
  // The model is centred: the centre pixel is not background, a corner is.
  const auto px = [&](const std::vector<std::uint8_t>& img, int x, int y) {
    return &img[(static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x)) * 4];
  };
  const std::uint8_t* corner = px(rest, 2, 2);
  const std::uint8_t* centre = px(rest, kW / 2, kH / 2);
  EXPECT_GT(std::abs(int{centre[0]} - int{corner[0]}) + std::abs(int{centre[1]} - int{corner[1]}),
            60);

  // A one-hand stroke grabbing the sphere's -Y side: pull out and twist.
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}), math::Frame{}};
  const std::array<math::Frame, 2> end{math::frame_from_uv({0.0, -0.16, -0.03}, {1.0, 0.0, 0.0},
                                                           {0.0, std::cos(0.6), std::sin(0.6)}),
                                       math::Frame{}};
  const LiveMessages live =
      make_live_messages(1, 1, math::WarpMethod::twister, 0.12, 1, start, end);
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  ASSERT_TRUE(r.live().active);
  renderer_.set_weights(r.live().weight1, r.live().weight2);
  renderer_.set_show_weights(true);
  renderer_.set_live(&r.live());
  renderer_.draw();
  const auto shader = renderer_.read_rgba();
  EXPECT_GT(differing(rest, shader, 8), 0.02);  // the stroke is visible

  // Same weights (colours), CPU-warped positions, no shader warp.
  renderer_.set_mesh(r.cpu_warp(), true);
  renderer_.set_weights(r.live().weight1, r.live().weight2);
  renderer_.set_show_weights(true);
  renderer_.set_live(nullptr);
  renderer_.draw();
  const auto cpu = renderer_.read_rgba();
  // Same geometry: the model covers the same pixels. Shading differs a little:
  // the shader turns the rest normals with the warp, the CPU path averages the
  // warped faces' normals.
  const double coverage = coverage_differs(shader, cpu);
  const double diff = differing(shader, cpu, 12);
  std::printf(
      "rest vs live: %.2f%% of pixels differ; shader vs CPU warp: coverage %.3f%%, colour %.3f%%\n",
      100.0 * differing(rest, shader, 8), 100.0 * coverage, 100.0 * diff);
  EXPECT_LT(coverage, 0.001) << "shader vs CPU warp cover different pixels";
  EXPECT_LT(diff, 0.01) << "shader vs CPU warp differ in " << diff * 100 << "% of pixels";

  // Where every weight is zero the shader leaves the rest mesh alone.
  std::vector<float> zero(r.mesh().vertex_count(), 0.0F);
  renderer_.set_mesh(r.mesh(), true);
  renderer_.set_weights(zero, zero);
  renderer_.set_show_weights(false);
  renderer_.set_live(&r.live());
  renderer_.draw();
  EXPECT_EQ(differing(rest, renderer_.read_rgba(), 0), 0.0);
  if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
    (void)write_png(std::string(dir) + "/render_rest.png", kW, kH, rest);
    (void)write_png(std::string(dir) + "/render_shader.png", kW, kH, shader);
    (void)write_png(std::string(dir) + "/render_cpu.png", kW, kH, cpu);
  }
}

// A connected link with nothing to say: BridgeApp::step() only refreshes the display.
class QuietLink final : public ports::LinkPort {
  Result<std::size_t> do_send(std::span<const std::byte> src) override { return src.size(); }
  Result<std::size_t> do_receive(std::span<std::byte>) override { return std::size_t{0}; }
};

TEST_F(BridgeRender, ScodefPreviewOfTheAppIsTheCpuWarpOfEachLiveFrame) {
  QuietLink link;
  ports::NullLogSink log;
  twister::test::FakeClock clock;
  BridgeApp app(link, clock, &renderer_, {}, log);
  load_mesh(app.replica(), sphere_mesh(0.1F));
  app.step();
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}), math::Frame{}};
  std::uint16_t sequence = 0;
  for (const double lift : {0.03, 0.06}) {
    const std::array<math::Frame, 2> end{math::identity_frame({0.0, -0.1 - lift, 0.0}),
                                         math::Frame{}};
    LiveMessages live = make_live_messages(1, 1, math::WarpMethod::scodef, 0.12, 1, start, end);
    live.hands.sequence = sequence++;
    (void)app.replica().apply(live.stroke);
    (void)app.replica().apply(live.hands);
    app.step();
    app.step();  // no new frame: the picture stays
    app.draw();
    const auto shown = renderer_.read_rgba();
    // What the preview is: the CPU warp as geometry, tinted by the stroke's weights.
    const SceneReplica& r = app.replica();
    renderer_.set_mesh(r.cpu_warp(), true);
    renderer_.set_weights(r.live().weight1, r.live().weight2);
    renderer_.draw();
    EXPECT_EQ(differing(shown, renderer_.read_rgba(), 0), 0.0) << lift;
  }
}

}  // namespace
}  // namespace twister::bridge
