// The display's heads-up text without GL (HudModel) and the weights it shows
// before a grab (WeightPreview): the same as the stroke's once the hands grab there.
#include <gtest/gtest.h>

#include <algorithm>

#include "bridge_image_rig.hpp"
#include "hud_model.hpp"
#include "twister/link/math_conversion.hpp"
#include "weight_preview.hpp"

namespace twister::bridge::test {
namespace {

link::StatusReport status(std::uint8_t tracker, std::uint32_t vertices, std::uint32_t capacity,
                          std::uint64_t not_saved = 0, std::uint64_t capacity_stops = 0) {
  link::StatusReport m;
  m.tracker_state = tracker;
  m.vertex_count = vertices;
  m.vertex_capacity = capacity;
  m.triangle_count = 2 * vertices;
  m.triangle_capacity = 4 * capacity;
  m.strokes.not_saved = not_saved;
  m.strokes.capacity_stops = capacity_stops;
  return m;
}

TEST(HudModel, BannersInOrderOfUrgency) {
  SceneReplica r;
  HudModel hud;
  HudInput in;
  in.link = LinkView::connected;
  in.ready = true;
  EXPECT_EQ(hud.update(r, in).banner, "");
  (void)r.apply(status(1, 100, 1000));
  EXPECT_EQ(hud.update(r, in).banner, "");
  (void)r.apply(status(1, 1000, 1000, 0, 1));  // a refined commit stopped at capacity
  EXPECT_EQ(hud.update(r, in).banner, "CAPACITY REACHED");
  in.now_s = 11.0;
  EXPECT_EQ(hud.update(r, in).banner, "") << "the capacity banner stays 10 s";
  (void)r.apply(status(2, 1000, 1000, 0, 1));
  EXPECT_EQ(hud.update(r, in).banner, "TRACKER LOST");
  in.link = LinkView::lost;
  const HudText lost = hud.update(r, in);
  EXPECT_EQ(lost.banner, "LINK LOST");
  EXPECT_NE(lost.lines[0].find("lost, reconnecting"), std::string::npos) << lost.lines[0];
  // A station that said goodbye at the end of its run: said, but no banner over the model.
  in.link = LinkView::stopped;
  const HudText stopped = hud.update(r, in);
  EXPECT_EQ(stopped.banner, "TRACKER LOST") << "the station's last status still counts";
  (void)r.apply(status(1, 1000, 1000));
  EXPECT_EQ(hud.update(r, in).banner, "");
  EXPECT_NE(hud.update(r, in).lines[0].find("the station stopped"), std::string::npos);
}

TEST(HudModel, AMeshLoadedFullIsNoBannerButSaysSo) {
  SceneReplica r;
  HudModel hud;
  (void)r.apply(status(1, 1000, 1000));
  const HudText t = hud.update(r, {LinkView::connected, true, 0.0, 0.0, 0.0});
  EXPECT_EQ(t.banner, "");
  EXPECT_TRUE(std::any_of(t.lines.begin(), t.lines.end(), [](const std::string& l) {
    return l.find("(full)") != std::string::npos;
  }));
}

TEST(HudModel, StrokeNotSavedStaysUpForTenSecondsAfterTheCountGrows) {
  SceneReplica r;
  HudModel hud;
  HudInput in{LinkView::connected, true, 60.0, 100.0, 120.0};
  (void)r.apply(status(1, 10, 1000, 0));
  EXPECT_EQ(hud.update(r, in).banner, "");
  (void)r.apply(status(1, 10, 1000, 1));
  EXPECT_EQ(hud.update(r, in).banner, "STROKE NOT SAVED");
  in.now_s = 109.0;
  EXPECT_EQ(hud.update(r, in).banner, "STROKE NOT SAVED");
  in.now_s = 111.0;
  EXPECT_EQ(hud.update(r, in).banner, "");
  (void)r.apply(status(1, 10, 1000, 2));
  EXPECT_EQ(hud.update(r, in).banner, "STROKE NOT SAVED");
  const HudText t = hud.update(r, in);
  EXPECT_NE(t.lines.back().find("60.0 fps"), std::string::npos) << t.lines.back();
}

// Issue 24: a live stroke the commit refines says how the preview is drawn.
TEST(HudModel, TheLivePreviewLineSaysRefinedOrWhyNot) {
  SceneReplica r;
  load_mesh(r, sphere_mesh(0.1F, 24, 32));
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}), {}};
  LiveMessages live = make_live_messages(1, 1, math::WarpMethod::twister, 0.08, 1, start, start);
  live.stroke.refine_threshold_m = 0.0005F;
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  ASSERT_TRUE(r.live().active);
  HudModel hud;
  HudInput in;
  in.preview = HudInput::Preview::refined;
  const auto has = [](const HudText& t, const char* text) {
    return std::any_of(t.lines.begin(), t.lines.end(),
                       [&](const std::string& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has(hud.update(r, in), "live preview: refined to 0.50 mm"));
  in.preview = HudInput::Preview::unrefined;
  EXPECT_TRUE(has(hud.update(r, in), "live preview: unrefined (needs OpenGL 4)"));
  in.preview = HudInput::Preview::none;
  EXPECT_FALSE(has(hud.update(r, in), "live preview"));
}

// Offscreen (issue 27): a picture is drawn when a message calls for it, so the
// HUD shows no frame rate and no per-second hands rate (SceneView passes fps 0 and
// a negative rate); the window's lines keep both.
TEST(HudModel, OffscreenLinesShowNoFrameRateAndNoHandsRate) {
  SceneReplica r;
  HudModel hud;
  (void)r.apply(status(1, 10, 1000, 0));
  const HudText window = hud.update(r, HudInput{LinkView::connected, true, 60.0, 1.0, 120.0});
  EXPECT_NE(window.lines.front().find("hands 120/s"), std::string::npos) << window.lines.front();
  EXPECT_NE(window.lines.back().find("fps"), std::string::npos) << window.lines.back();
  const HudText offscreen = hud.update(r, HudInput{LinkView::connected, true, 0.0, 1.0, -1.0});
  EXPECT_EQ(offscreen.lines.front().find("/s"), std::string::npos) << offscreen.lines.front();
  EXPECT_NE(offscreen.lines.front().find("hands missed 0"), std::string::npos);
  EXPECT_EQ(offscreen.lines.back().find("fps"), std::string::npos) << offscreen.lines.back();
}

TEST(WeightPreview, EqualsTheStrokesWeightsWhenTheHandsGrabThere) {
  SceneReplica r;
  load_mesh(r, sphere_mesh(0.1F, 24, 32));
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}),
                                         math::identity_frame({0.0, -0.08, 0.05})};
  std::array<HandView, 2> hands{};
  for (std::size_t h = 0; h < 2; ++h) {
    hands[h].present = true;
    hands[h].pose = start[h];
  }
  WeightPreview preview;
  ASSERT_TRUE(preview.update(r.mesh(), r.version(), hands, 0.08));
  EXPECT_FALSE(preview.update(r.mesh(), r.version(), hands, 0.08)) << "rebuilt for nothing";
  const LiveMessages live =
      make_live_messages(1, 1, math::WarpMethod::twister, 0.08, 3, start, start);
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  ASSERT_TRUE(r.live().active);
  EXPECT_EQ(preview.hand1(), r.live().weight1);
  EXPECT_EQ(preview.hand2(), r.live().weight2);
  const auto influenced = std::count_if(preview.hand1().begin(), preview.hand1().end(),
                                        [](float w) { return w > 0.0F; });
  EXPECT_GT(influenced, 20);
  // The balls overlap: hand 2's squash shrinks hand 1's reach towards it.
  hands[1].present = false;
  ASSERT_TRUE(preview.update(r.mesh(), r.version(), hands, 0.08));
  EXPECT_GT(std::count_if(preview.hand1().begin(), preview.hand1().end(),
                          [](float w) { return w > 0.0F; }),
            influenced);
  EXPECT_EQ(preview.hand_mask(), 1u);
}

}  // namespace
}  // namespace twister::bridge::test
