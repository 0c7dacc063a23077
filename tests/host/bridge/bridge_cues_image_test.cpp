// Image tests of what the sculptor sees (issue 14), under Mesa's software renderer:
// offscreen (EGL surfaceless + FBO) by default, in a GLFW window when run with
// TWISTER_TEST_DISPLAY=window under Xvfb (CTest runs both). Known 3D points are
// projected through the display's camera and the pixels there are classified:
// a cursor at each hand, red/green tint near each hand before a grab, the sphere
// of influence, pink along each projected screw axis, yellow along each grab
// point's trajectory, the object frame while moving the object, text in the HUD
// panel and a full-screen banner. Each test also draws the frame without the cue
// and checks the pixels lose it, so a missing cue fails.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "bridge_image_rig.hpp"
#include "twister/link/math_conversion.hpp"

namespace twister::bridge::test {
namespace {

constexpr float kSphereM = 0.1F;
constexpr float kRadiusM = 0.06F;

class DisplayCues : public DisplayRig {
 protected:
  void SetUp() override {
    DisplayRig::SetUp();
    if (HasFatalFailure()) return;
    load_mesh(app_->replica(), sphere_mesh(kSphereM));
    app_->step();  // uploads the mesh and frames the camera
  }
  // Points just off the sphere on the side facing the camera, left and right.
  glm::dvec3 hand_point(int side) const {
    const Camera& c = renderer_.camera();
    const glm::vec3 right = glm::normalize(glm::cross(-c.direction(), c.up()));
    const glm::vec3 d = glm::normalize(0.75F * c.direction() + 0.66F * float(side) * right);
    return glm::dvec3(1.03F * kSphereM * d);
  }
  void send_hands(std::array<bool, 2> present, std::uint8_t buttons = 0) {
    link::Hands m;
    m.sequence = sequence_++;
    m.radius_m = kRadiusM;
    m.buttons = buttons;
    for (std::size_t h = 0; h < 2; ++h) {
      if (!present[h]) continue;
      m.flags = static_cast<std::uint8_t>(m.flags | (link::kHandSample0 << h) |
                                          (link::kHandTracked0 << h));
      m.hands[h] = link::to_compact(math::identity_frame(hand_point(h == 0 ? -1 : 1)));
    }
    (void)app_->replica().apply(m);
  }
  void send_status(std::uint8_t tracker_state) {
    link::StatusReport m;
    m.tracker_state = tracker_state;
    m.tracker_rate_hz = 120.0F;
    m.vertex_count = static_cast<std::uint32_t>(app_->replica().mesh().vertex_count());
    m.vertex_capacity = 100000;
    m.triangle_capacity = 200000;
    (void)app_->replica().apply(m);
  }
  glm::vec2 at(glm::dvec3 p) const {
    const auto px = project_object(p);
    EXPECT_TRUE(px.has_value());
    return px.value_or(glm::vec2(-100.0F));
  }
  std::uint16_t sequence_ = 0;
};

TEST_F(DisplayCues, WeightsTintTheMeshNearEachHandBeforeAGrab) {
  view_->options().cues.glyphs = false;  // the tint alone: no cursor, axes or balls
  view_->options().cues.spheres = false;
  const Image none = frame();
  expect_live_frame(none);
  send_hands({true, true});
  const Image both = frame();
  expect_live_frame(both);
  const glm::vec2 h1 = at(hand_point(-1));
  const glm::vec2 h2 = at(hand_point(1));
  EXPECT_EQ(count_near(none, h1, 20, is_red), 0);
  EXPECT_EQ(count_near(none, h2, 20, is_green), 0);
  EXPECT_GT(count_near(both, h1, 20, is_red), 60) << "no red tint near hand 1";
  EXPECT_GT(count_near(both, h2, 20, is_green), 60) << "no green tint near hand 2";
  EXPECT_EQ(count_near(both, h1, 20, is_green), 0) << "green tint near hand 1";
  EXPECT_EQ(count_near(both, h2, 20, is_red), 0) << "red tint near hand 2";
}

TEST_F(DisplayCues, CursorAtEachHandAndItsSphereOfInfluence) {
  const Image none = frame();
  send_hands({true, true});
  const Image both = frame();
  expect_live_frame(both);
  const glm::vec2 h1 = at(hand_point(-1));
  const glm::vec2 h2 = at(hand_point(1));
  EXPECT_TRUE(is_red(both.at(int(h1.x), int(h1.y)))) << "no red cursor at hand 1";
  EXPECT_TRUE(is_green(both.at(int(h2.x), int(h2.y)))) << "no green cursor at hand 2";
  // The cursor's own colour, drawn over everything: without the glyphs the pixel
  // there is the (tinted) model's, far from it.
  const auto cursor_like = [](std::array<int, 3> c, std::array<int, 3> want) {
    return std::abs(c[0] - want[0]) + std::abs(c[1] - want[1]) + std::abs(c[2] - want[2]) < 40;
  };
  const std::array<int, 3> red{235, 36, 31};
  const std::array<int, 3> green{38, 217, 31};
  EXPECT_TRUE(cursor_like(both.at(int(h1.x), int(h1.y)), red));
  EXPECT_TRUE(cursor_like(both.at(int(h2.x), int(h2.y)), green));
  view_->options().cues.glyphs = false;
  const Image bare = frame();
  EXPECT_FALSE(cursor_like(bare.at(int(h1.x), int(h1.y)), red))
      << "hand 1's pixel is cursor-red anyway";
  EXPECT_FALSE(cursor_like(bare.at(int(h2.x), int(h2.y)), green));
  // Off the model, 80 % of the radius outwards from hand 1: the translucent ball
  // reddens the background.
  const glm::dvec3 out = hand_point(-1) + 0.8 * kRadiusM * glm::normalize(hand_point(-1));
  const glm::dvec3 side =
      hand_point(-1) + 0.8 * kRadiusM *
                           glm::dvec3(glm::normalize(glm::cross(renderer_.camera().up(),
                                                                renderer_.camera().direction())));
  int reddened = 0;
  for (const glm::dvec3& p : {out, side}) {
    const glm::vec2 px = at(p);
    const auto a = none.at(int(px.x), int(px.y));
    const auto b = both.at(int(px.x), int(px.y));
    reddened += (b[0] - a[0]) - (b[1] - a[1]) > 12 ? 1 : 0;
  }
  EXPECT_GE(reddened, 1) << "no sphere of influence around hand 1";
}

// A two-hand stroke: both hands pull out and turn about the X axis in opposite senses.
LiveMessages stroke_messages(double angle) {
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}),
                                         math::identity_frame({0.0, 0.1, 0.0})};
  const auto turned = [](glm::dvec3 o, double a) {
    return math::frame_from_uv(o, {1.0, 0.0, 0.0}, {0.0, std::cos(a), std::sin(a)});
  };
  const std::array<math::Frame, 2> end{turned({0.02, -0.14, -0.03}, angle),
                                       turned({0.02, 0.14, -0.03}, -angle)};
  return make_live_messages(1, 1, math::WarpMethod::twister, 0.08, 3, start, end);
}

// Fraction of `points` (object frame) whose pixel has a `pred` pixel within 2 px,
// skipping points off the image, on a cursor or under the HUD panel.
template <typename Pred>
double fraction_along(const DisplayCues& t, const Image& img, const std::vector<glm::dvec3>& points,
                      const std::vector<glm::vec2>& cursors, const float* panel, Pred pred,
                      int& used) {
  int hits = 0;
  used = 0;
  for (const glm::dvec3& p : points) {
    const auto px = t.renderer().camera().project(
        glm::vec3(t.renderer().model_matrix() * glm::vec4(glm::vec3(p), 1.0F)), img.width,
        img.height);
    if (!px || px->x < 3 || px->y < 3 || px->x > float(img.width - 4) ||
        px->y > float(img.height - 4)) {
      continue;
    }
    bool skip = px->x < panel[0] + panel[2] && px->y < panel[1] + panel[3];
    for (const glm::vec2& c : cursors) skip = skip || glm::distance(c, *px) < 10.0F;
    if (skip) continue;
    ++used;
    hits += near(img, *px, 2, pred) ? 1 : 0;
  }
  return used > 0 ? double(hits) / double(used) : 0.0;
}

TEST_F(DisplayCues, StrokeShowsPinkScrewAxesAndYellowTrajectories) {
  const LiveMessages live = stroke_messages(0.7);
  (void)app_->replica().apply(live.stroke);
  (void)app_->replica().apply(live.hands);
  ASSERT_TRUE(app_->replica().live().active);
  const Image with = frame();
  expect_live_frame(with);
  view_->options().cues.screw_axes = false;
  view_->options().cues.trajectories = false;
  const Image without = frame();
  const LiveState& state = app_->replica().live();
  std::vector<glm::vec2> cursors;
  for (std::size_t k = 0; k < state.hands.size(); ++k)
    cursors.push_back(at(state.hands[k].end.origin));
  for (std::size_t k = 0; k < state.hands.size(); ++k) {
    const LiveHand& hand = state.hands[k];
    const auto axis = screw_axis_segment(hand, state.method, 0.8 * renderer_.model_radius());
    ASSERT_TRUE(axis.has_value());
    std::vector<glm::dvec3> on_axis;
    for (int i = 0; i <= 24; ++i) on_axis.push_back(glm::mix(axis->first, axis->second, i / 24.0));
    const std::vector<glm::dvec3> path = stroke_trajectory(hand, state.method, 21);
    const std::vector<glm::dvec3> inner(path.begin() + 1, path.end() - 1);
    int used = 0;
    const double pink =
        fraction_along(*this, with, on_axis, cursors, view_->hud().panel(), is_pink, used);
    EXPECT_GE(used, 10) << "axis " << k << " mostly off the picture";
    EXPECT_GE(pink, 0.75) << "axis " << k << ": pink at " << pink * 100 << "% of " << used;
    const double yellow =
        fraction_along(*this, with, inner, cursors, view_->hud().panel(), is_yellow, used);
    EXPECT_GE(used, 8) << "trajectory " << k << " mostly off the picture";
    EXPECT_GE(yellow, 0.75) << "trajectory " << k << ": yellow at " << yellow * 100 << "%";
    // The same frame without those cues has neither colour there.
    EXPECT_LT(fraction_along(*this, without, on_axis, cursors, view_->hud().panel(), is_pink, used),
              0.2);
    EXPECT_LT(fraction_along(*this, without, inner, cursors, view_->hud().panel(), is_yellow, used),
              0.2);
  }
}

TEST_F(DisplayCues, HudPanelHoldsTheStationsState) {
  send_status(1);
  send_hands({true, false});
  const Image with = frame();
  expect_live_frame(with);
  const HudText& text = view_->hud_text();
  ASSERT_GE(text.lines.size(), 8u);
  EXPECT_EQ(text.lines[1], "tracker: streaming, 120 poses/s   buttons: present");
  EXPECT_TRUE(text.banner.empty()) << text.banner;
  const float* panel = view_->hud().panel();
  ASSERT_GT(panel[2], 100.0F);
  ASSERT_GT(panel[3], 100.0F);
  // Glyph edges: a bright pixel beside a dark one (smooth shading has none).
  const auto text_pixels = [&panel](const Image& img) {
    int n = 0;
    for (int y = int(panel[1]); y < int(panel[1] + panel[3]); ++y) {
      for (int x = int(panel[0]); x < int(panel[0] + panel[2]); ++x) {
        const auto a = img.at(x, y);
        const auto b = img.at(x + 1, y);
        n += std::abs(a[0] + a[1] + a[2] - b[0] - b[1] - b[2]) > 300 ? 1 : 0;
      }
    }
    return n;
  };
  const int area = int(panel[2] * panel[3]);
  EXPECT_GT(text_pixels(with), area / 100) << "no text in the HUD panel";
  view_->options().hud = false;
  EXPECT_LT(text_pixels(frame()), area / 500) << "the panel's text came from elsewhere";
}

TEST_F(DisplayCues, TrackerLostIsAFullScreenBanner) {
  send_status(1);
  const Image fine = frame();
  send_status(2);
  const Image lost = frame();
  expect_live_frame(lost);
  EXPECT_EQ(view_->hud_text().banner, "TRACKER LOST");
  const auto banner_red = [](std::array<int, 3> c) {
    return c[0] > 80 && c[0] - c[1] > 50 && c[0] - c[2] > 50;
  };
  const auto white = [](std::array<int, 3> c) { return c[0] > 200 && c[1] > 200 && c[2] > 200; };
  const glm::vec2 centre(kW / 2.0F, kH / 2.0F);
  EXPECT_GT(count_near(lost, centre, 40, banner_red), 1500) << "no banner across the middle";
  EXPECT_GT(count_near(lost, centre, 40, white), 100) << "no text in the banner";
  EXPECT_LT(count_near(fine, centre, 40, banner_red), 50);
}

TEST_F(DisplayCues, ObjectFrameWhileMovingTheObject) {
  link::ObjectPose object;
  object.pose = link::to_compact(math::identity_frame({0.0, 0.0, 0.04}));
  (void)app_->replica().apply(object);
  send_hands({true, false});
  const Image still = frame();
  send_hands({true, false}, link::kButtonMoveObject);
  const Image moving = frame();
  // The object frame's axes, halfway along each (world frame: the object pose).
  const float len = 0.25F * renderer_.model_radius();
  const auto world = [&](glm::vec3 d) {
    return *renderer_.camera().project(glm::vec3(0.0F, 0.0F, 0.04F) + len * d, kW, kH);
  };
  const auto blue = [](std::array<int, 3> c) { return c[2] - c[0] > 50 && c[2] - c[1] > 30; };
  EXPECT_GT(count_near(moving, world({1, 0, 0}), 2, is_red), 0) << "no U axis (red)";
  EXPECT_GT(count_near(moving, world({0, 1, 0}), 2, is_green), 0) << "no V axis (green)";
  EXPECT_GT(count_near(moving, world({0, 0, 1}), 2, blue), 0) << "no W axis (blue)";
  EXPECT_EQ(count_near(still, world({0, 0, 1}), 2, blue), 0);
}

}  // namespace
}  // namespace twister::bridge::test
