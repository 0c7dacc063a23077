// The display's camera (framing, orbit, zoom, pan, projection), the kiosk's camera
// file, and the window's keys: camera keys move a free camera and not a fixed one;
// Z / Y / M reach the station's command queue over the link (no GL needed).
#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <span>

#include "bridge_link_rig.hpp"
#include "camera_config.hpp"
#include "framing.hpp"
#include "window_input.hpp"

namespace twister::bridge {
namespace {

TEST(Camera, FramesTheModelAndProjectsItsCentreToTheMiddle) {
  Camera c;
  c.frame(glm::vec3(0.5F, 0.0F, 0.1F), 0.2F);
  const auto centre = c.project(glm::vec3(0.5F, 0.0F, 0.1F), 800, 600);
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x, 400.0F, 0.5F);
  EXPECT_NEAR(centre->y, 300.0F, 0.5F);
  // The bounding sphere fits: a point on it along the screen's up stays inside.
  const auto top = c.project(glm::vec3(0.5F, 0.0F, 0.1F) + 0.2F * c.up(), 800, 600);
  ASSERT_TRUE(top);
  EXPECT_GT(top->y, 0.0F);
  EXPECT_LT(top->y, 300.0F) << "screen up is up";
  const float d = c.distance();
  c.zoom(2.0F);
  EXPECT_NEAR(c.distance(), d / 2.0F, 1e-5F);
  const glm::vec3 eye = c.eye();
  c.orbit(30.0F, 0.0F);
  EXPECT_GT(glm::distance(eye, c.eye()), 0.01F);
  c.pan(0.5F, 0.0F);  // half the view's height to the right
  const auto moved = c.project(glm::vec3(0.5F, 0.0F, 0.1F), 800, 600);
  EXPECT_NEAR(moved->x, 100.0F, 2.0F);
  c.reset();
  EXPECT_NEAR(c.distance(), d, 1e-5F);
  EXPECT_NEAR(c.project(glm::vec3(0.5F, 0.0F, 0.1F), 800, 600)->x, 400.0F, 0.5F);
}

TEST(CameraConfig, TheKioskExampleAndEveryKey) {
  const auto example =
      load_camera_config(TWISTER_SOURCE_DIR "/host/twister-bridge/kiosk_camera.toml");
  ASSERT_TRUE(example) << example.error().message;
  EXPECT_TRUE(example->fixed);
  EXPECT_EQ(example->view.azimuth_deg, 200.0F);
  const auto c = parse_camera_config(
      "[camera]\nazimuth_deg = 90\nelevation_deg = -10.5\nzoom = 2.0\nfov_deg = 50\n"
      "up = [0, 1, 0]\ntarget = [0.5, 0.25, 0]\nfixed = false\n",
      "k.toml");
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->view.azimuth_deg, 90.0F);
  EXPECT_EQ(c->view.elevation_deg, -10.5F);
  EXPECT_EQ(c->view.zoom, 2.0F);
  EXPECT_EQ(c->view.fov_deg, 50.0F);
  EXPECT_EQ(c->view.up[1], 1.0F);
  EXPECT_TRUE(c->view.has_target);
  EXPECT_EQ(c->view.target[1], 0.25F);
  EXPECT_FALSE(c->fixed);
  Camera fixed(c->view);
  fixed.frame(glm::vec3(9.0F), 1.0F);  // the target wins over the model's centre
  EXPECT_EQ(fixed.target(), glm::vec3(0.5F, 0.25F, 0.0F));
}

TEST(CameraConfig, MistakesNameTheKey) {
  const auto error = [](const std::string& text) {
    const auto c = parse_camera_config(text, "k.toml");
    return c ? std::string("accepted") : c.error().message;
  };
  EXPECT_NE(error("[camera]\nzom = 2\n").find("camera.zom: unknown key"), std::string::npos);
  EXPECT_NE(error("[camera]\nelevation_deg = 95\n").find("camera.elevation_deg"),
            std::string::npos);
  EXPECT_NE(error("[camera]\nzoom = \"near\"\n").find("camera.zoom"), std::string::npos);
  EXPECT_NE(error("[camera]\nup = [0, 0]\n").find("camera.up"), std::string::npos);
  EXPECT_NE(error("[camera]\nup = [0, 0, 0]\n").find("non-zero"), std::string::npos);
  EXPECT_NE(error("[camera]\nfixed = 1\n").find("camera.fixed"), std::string::npos);
  EXPECT_NE(error("[view]\n").find("view: unknown"), std::string::npos);
  EXPECT_NE(error("[camera\n").find("k.toml:1: TOML syntax error"), std::string::npos);
  EXPECT_FALSE(load_camera_config("/nonexistent/k.toml"));
  // Attract mode's showcase (issue 25).
  EXPECT_NE(error("[attract]\nmodels = 0\n").find("attract.models"), std::string::npos);
  EXPECT_NE(error("[attract]\nmodels = 2.5\n").find("attract.models"), std::string::npos);
  EXPECT_NE(error("[attract]\nseconds = 0.2\n").find("attract.seconds"), std::string::npos);
  EXPECT_NE(error("[attract]\narchive = \"\"\n").find("attract.archive"), std::string::npos);
  EXPECT_NE(error("[attract]\narchiv = \"x\"\n").find("attract.archiv: unknown key"),
            std::string::npos);
  const auto a = parse_camera_config(
      "[attract]\narchive = \"/srv/archive\"\nmodels = 3\nseconds = 12.5\n", "k.toml");
  ASSERT_TRUE(a) << a.error().message;
  EXPECT_EQ(a->attract.archive, "/srv/archive");
  EXPECT_EQ(a->attract.models, 3);
  EXPECT_EQ(a->attract.seconds, 12.5);
  EXPECT_TRUE(a->fixed);  // no [camera]: its defaults
}

TEST(WindowInput, CameraKeysMoveAFreeCameraOnlyAndCommandKeysReachTheStation) {
  ports::NullLogSink log;
  test_support::BridgeLinkRig rig(log);
  MeshRenderer renderer;  // no GL: the camera only
  SceneView view(renderer, rig.clock);
  renderer.camera().frame(glm::vec3(0.0F), 0.1F);
  const glm::vec3 eye = renderer.camera().eye();
  WindowInput kiosk(rig.bridge, view, true);
  EXPECT_FALSE(kiosk.apply(key_action(GLFW_KEY_LEFT)));
  kiosk.mouse_button(GLFW_MOUSE_BUTTON_LEFT, true, 10.0, 10.0);
  kiosk.cursor(200.0, 50.0);
  kiosk.scroll(3.0);
  EXPECT_EQ(renderer.camera().eye(), eye) << "a fixed camera moved";
  EXPECT_FALSE(kiosk.apply(key_action(GLFW_KEY_Z))) << "a command before the handshake";
  rig.run();
  ASSERT_TRUE(rig.bridge.ready());
  EXPECT_TRUE(kiosk.apply(key_action(GLFW_KEY_Z)));
  WindowInput desk(rig.bridge, view, false);
  EXPECT_TRUE(desk.apply(key_action(GLFW_KEY_Y)));
  EXPECT_TRUE(desk.apply(key_action(GLFW_KEY_M)));
  EXPECT_TRUE(desk.apply(key_action(GLFW_KEY_LEFT)));
  EXPECT_NE(renderer.camera().eye(), eye);
  desk.mouse_button(GLFW_MOUSE_BUTTON_LEFT, true, 10.0, 10.0);
  const glm::vec3 before_drag = renderer.camera().eye();
  desk.cursor(60.0, 10.0);
  EXPECT_NE(renderer.camera().eye(), before_drag) << "a drag did not orbit";
  EXPECT_TRUE(desk.apply(key_action(GLFW_KEY_H)));
  EXPECT_FALSE(view.options().hud);
  rig.run(2);
  // Z, Y, M reached the station's session (undo, redo, next method).
  EXPECT_EQ(rig.link->counters().commands, 3u);
  EXPECT_EQ(rig.link->counters().commands_refused, 0u);
  (void)rig.station.tick();
  EXPECT_EQ(rig.station.session->method(), math::WarpMethod::rottran);
}

}  // namespace
}  // namespace twister::bridge

namespace twister::bridge {
namespace {

// The workspace framing (kiosk, offscreen): a cursor that leaves the framed sphere
// makes it grow over several updates, never by a jump and never back; a cursor inside
// changes nothing; the volume and the model are both held.
TEST(WorkspaceFraming, HoldsTheVolumeAndTheModel) {
  WorkspaceFraming f;
  f.hold({-0.3F, -0.3F, 0.0F}, {0.3F, 0.3F, 0.4F}, Sphere{{0.0F, 0.0F, 0.05F}, 0.09F});
  ASSERT_TRUE(f.active());
  EXPECT_NEAR(f.sphere().radius, 0.5F * std::sqrt(0.36F + 0.36F + 0.16F), 1e-5F);
  // A model beyond the volume is held too.
  f.hold({-0.3F, -0.3F, 0.0F}, {0.3F, 0.3F, 0.4F}, Sphere{{1.0F, 0.0F, 0.2F}, 0.1F});
  EXPECT_LE(glm::length(glm::vec3(1.0F, 0.0F, 0.2F) - f.sphere().centre) + 0.1F,
            f.sphere().radius * 1.0001F);
}

TEST(WorkspaceFraming, GrowsSmoothlyToKeepACursorThatLeavesAndNeverShrinks) {
  WorkspaceFraming f;
  f.hold({-0.3F, -0.3F, 0.0F}, {0.3F, 0.3F, 0.4F}, Sphere{{0.0F, 0.0F, 0.05F}, 0.09F});
  const Sphere start = f.sphere();
  const glm::vec3 inside(0.1F, 0.1F, 0.2F);
  EXPECT_FALSE(f.follow(std::span<const glm::vec3>(&inside, 1)));
  EXPECT_EQ(f.sphere().radius, start.radius);
  // A hand far outside: the framing grows over several updates, each a bounded step.
  const glm::vec3 out(0.9F, 0.0F, 0.2F);
  float radius = f.sphere().radius;
  int updates = 0;
  for (; updates < 100; ++updates) {
    const glm::vec3 c = f.sphere().centre;
    if (!f.follow(std::span<const glm::vec3>(&out, 1))) break;
    EXPECT_GE(f.sphere().radius, radius) << "never shrinks";
    EXPECT_LE(f.sphere().radius - radius, 0.1F) << "no jump at update " << updates;
    EXPECT_LE(glm::length(f.sphere().centre - c), 0.1F) << "no jump at update " << updates;
    radius = f.sphere().radius;
  }
  EXPECT_GT(updates, 3) << "it eased, not jumped";
  EXPECT_LE(glm::length(out - f.sphere().centre), f.sphere().radius) << "the cursor is held";
  // The hand comes back: the framing stays.
  EXPECT_FALSE(f.follow(std::span<const glm::vec3>(&inside, 1)));
  EXPECT_EQ(f.sphere().radius, radius);
}

}  // namespace
}  // namespace twister::bridge
