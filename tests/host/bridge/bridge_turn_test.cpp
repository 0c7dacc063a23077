// The display of a stroke turned past 180 degrees (docs/unwrap.md), over link
// protocol 2: the station sends the end pose's rotation as a signed quaternion, so
// the bridge rebuilds the station's screw the long way round (angle up to 2 pi,
// negative cot(a/2)); its CPU warp and the vertex shader then draw what the station
// computes. A real SculptSession behind StationLink and a headless BridgeApp on an
// in-memory wire. Label interaction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "bridge_link_rig.hpp"
#include "bridge_test_mesh.hpp"
#include "gl_context.hpp"
#include "hud_model.hpp"
#include "mesh_renderer.hpp"

namespace twister::bridge {
namespace {

using test::differing;
using test_support::warp_difference;

using session::test_support::kGrab0;
using session::test_support::z_turn;

constexpr double kPi = std::numbers::pi;

struct Rig : test_support::BridgeLinkRig {
  Rig() : BridgeLinkRig(null_log) {}
  static inline ports::NullLogSink null_log;
  void step() {
    (void)station.tick();
    run(2);
  }
  // One hand grabs at the origin and turns about z to `turn`, in steps a tracker
  // would see (each well under a half turn, so the station unwraps the angle).
  void twist(double turn) {
    run();
    station.hand(0, math::identity_frame({0, 0, 0}));
    station.button(kGrab0, true);
    step();
    constexpr int kSteps = 12;
    for (int k = 1; k <= kSteps; ++k) {
      station.hand(0, z_turn({0.02 * k / kSteps, 0, 0.05 * k / kSteps}, turn * k / kSteps));
      step();
    }
  }
};

TEST(BridgeTurn, TheBridgeRebuildsTheStationsScrewPast180Degrees) {
  for (const double turn : {0.8 * kPi, 1.5 * kPi, 1.8 * kPi}) {
    Rig r;
    r.twist(turn);
    const math::Screw& station = r.station.session->live().plan->screw(0);
    ASSERT_NEAR(station.angle, turn, 1e-9);
    ASSERT_TRUE(r.bridge.replica().live().active);
    const math::Screw& bridge = r.bridge.replica().live().hands[0].screw;
    EXPECT_NEAR(bridge.angle, station.angle, 1e-5) << turn;
    EXPECT_GT(glm::dot(bridge.axis, station.axis), 0.9999) << turn;
    if (turn > kPi) {
      EXPECT_LT(bridge.cot_half, 0.0) << turn;
    }
    const double d = warp_difference(r);
    EXPECT_GE(d, 0.0);
    EXPECT_LT(d, 2e-5) << turn;
  }
}

// The heads-up text shows the angle turned as the hands turn (the live screws), not
// the status's once-a-second copy (this rig sends no StationStatus, so no limit).
TEST(BridgeTurn, TheHudShowsTheTurnPast180DegreesAsItHappens) {
  Rig r;
  r.twist(1.5 * kPi);
  ASSERT_TRUE(r.bridge.replica().has_status());
  HudModel hud;
  const HudText text = hud.update(r.bridge.replica(), HudInput{});
  bool found = false;
  for (const std::string& line : text.lines) {
    found = found || line.find("turn: 270 ") != std::string::npos;
  }
  EXPECT_TRUE(found) << (text.lines.size() > 2 ? text.lines[2] : std::string{});
}

// The vertex shader's warp of a 270-degree twist equals the CPU warp drawn as plain
// geometry, and differs clearly from the same poses' minimal (-90 degree) screw.
TEST(BridgeTurn, TheShaderDrawsA270DegreeTwistAsTheCpuWarps) {
  constexpr int kW = 320, kH = 240;
  auto context = make_offscreen_context(kW, kH);
  ASSERT_TRUE(context) << context.error().message;
  MeshRenderer renderer;
  ASSERT_TRUE(renderer.init(kW, kH, true, ViewConfig{}));
  Rig r;
  r.twist(1.5 * kPi);
  const SceneReplica& rep = r.bridge.replica();
  ASSERT_TRUE(rep.live().active);
  renderer.set_mesh(rep.mesh(), false);
  renderer.set_weights(rep.live().weight1, rep.live().weight2);
  renderer.set_show_weights(true);
  renderer.set_live(&rep.live());
  renderer.draw();
  const auto shader = renderer.read_rgba();

  renderer.set_mesh(rep.cpu_warp(), true);
  renderer.set_weights(rep.live().weight1, rep.live().weight2);
  renderer.set_live(nullptr);
  renderer.draw();
  const auto cpu = renderer.read_rgba();

  LiveState minimal = rep.live();  // what a display folding the turn would draw
  minimal.hands[0].screw = math::compute_screw(minimal.hands[0].start, minimal.hands[0].end);
  renderer.set_mesh(rep.mesh(), true);
  renderer.set_live(&minimal);
  renderer.draw();
  const auto folded = renderer.read_rgba();
  const double same = differing(shader, cpu, 12);
  const double other = differing(shader, folded, 12);
  std::printf("270-degree twist: shader vs CPU %.3f%% of pixels, vs the minimal screw %.2f%%\n",
              100.0 * same, 100.0 * other);
  EXPECT_LT(same, 0.002);
  EXPECT_GT(other, 0.005);
}

}  // namespace
}  // namespace twister::bridge
