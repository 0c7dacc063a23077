// Issue 25 (label exhibit), as pictures under Mesa's software renderer (offscreen EGL):
// attract mode (the model turning, centred, with the invitation), the visitor view
// (the model and a few friendly words, no technical panel), the operator HUD (the
// technical lines with the visitor line, no frame rate offscreen) and a notice's
// strip. Text is found as glyph edges (a bright pixel beside a dark one) inside the
// rectangle the HUD reports, and its absence where nothing should be written.
// With TWISTER_BRIDGE_TEST_PNG=DIR each frame is written there (docs/pictures'
// exhibit-*.png come from such a run).
#include <gtest/gtest.h>

#include <cmath>

#include "attract_showcase.hpp"
#include "bridge_image_rig.hpp"
#include "showcase_archive.hpp"
#include "twister/link/math_conversion.hpp"
#include "window_input.hpp"

namespace twister::bridge::test {
namespace {

constexpr float kModelM = 0.1F;

// A lumpy sphere: something a visitor might have made (and a turn shows).
MeshData lumpy_mesh() {
  MeshData m = sphere_mesh(kModelM);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const float x = m.x[i], y = m.y[i], z = m.z[i];
    const float r = std::sqrt(x * x + y * y + z * z);
    const float theta = std::acos(std::clamp(z / r, -1.0F, 1.0F));
    const float phi = std::atan2(y, x);
    const float s = 1.0F + 0.18F * std::sin(3.0F * theta) * std::cos(2.0F * phi) +
                    0.25F * std::max(0.0F, -z / r) * std::max(0.0F, -z / r);
    m.x[i] = x * s;
    m.y[i] = y * s;
    m.z[i] = z * s * 1.2F;
  }
  return m;
}

// Glyph edges inside rectangle r (x, y, w, h).
int text_pixels(const Image& img, const float* r) {
  int n = 0;
  for (int y = int(r[1]); y < int(r[1] + r[3]); ++y) {
    for (int x = int(r[0]); x < int(r[0] + r[2]); ++x) {
      const auto a = img.at(x, y);
      const auto b = img.at(x + 1, y);
      n += std::abs(a[0] + a[1] + a[2] - b[0] - b[1] - b[2]) > 300 ? 1 : 0;
    }
  }
  return n;
}

class ExhibitPictures : public DisplayRig {
 protected:
  void SetUp() override {
    options_.offscreen = true;  // as twister-bridge --offscreen draws
    DisplayRig::SetUp();
    if (HasFatalFailure()) return;
    load_mesh(app_->replica(), lumpy_mesh());
    app_->step();  // uploads the mesh and frames the camera
  }
  // A frame as an admitted display draws it (the rig's link never shakes hands).
  Image shot(Audience audience) {
    view_->options().audience = audience;
    app_->step();
    HudInput in = app_->hud_input();  // the showcase's caption among it
    in.link = LinkView::connected;
    in.ready = true;
    view_->draw(app_->replica(), in);
    Image img{renderer_.width(), renderer_.height(), renderer_.read_rgba()};
    if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
      (void)write_png(std::string(dir) + "/" + name() + ".png", img.width, img.height, img.rgba);
    }
    return img;
  }
  void phase(link::VisitorPhase p, std::uint32_t strokes = 0, float idle = 0.0F,
             std::uint8_t flags = 0, float grace = 0.0F) {
    link::VisitorState v;
    v.phase = p;
    v.visitor = 12;
    v.sculpture = 112;
    v.strokes = strokes;
    v.idle_left_s = idle;
    v.flags = flags;
    v.grace_left_s = grace;
    (void)app_->replica().apply(v);
  }
  void status() {
    link::StatusReport m;
    m.tracker_state = 1;
    m.tracker_rate_hz = 120.0F;
    m.vertex_count = static_cast<std::uint32_t>(app_->replica().mesh().vertex_count());
    m.vertex_capacity = 100000;
    m.triangle_capacity = 200000;
    (void)app_->replica().apply(m);
  }
  void hands(bool grab) {
    link::Hands m;
    m.sequence = sequence_++;
    m.radius_m = 0.05F;
    m.buttons = grab ? 1 : 0;
    m.flags = link::kHandSample0 | link::kHandTracked0 | link::kHandSample1 | link::kHandTracked1;
    m.hands[0] = link::to_compact(math::identity_frame({-1.3 * kModelM, 0.0, 0.0}));
    m.hands[1] = link::to_compact(math::identity_frame({1.3 * kModelM, 0.0, 0.0}));
    (void)app_->replica().apply(m);
  }
  // The centre of what is not background, above the prompt (pixels).
  glm::vec2 model_centre(const Image& img, float below_y) const {
    double sx = 0.0, sy = 0.0, n = 0.0;
    for (int y = 0; y < int(below_y); y += 2) {
      for (int x = 0; x < img.width; x += 2) {
        if (is_background(img.at(x, y))) continue;
        sx += x;
        sy += y;
        n += 1.0;
      }
    }
    return n > 0 ? glm::vec2(float(sx / n), float(sy / n)) : glm::vec2(-1.0F);
  }
  std::uint16_t sequence_ = 0;
};

TEST_F(ExhibitPictures, AttractModeTurnsTheModelCentredAndInvites) {
  status();
  phase(link::VisitorPhase::attract);
  const Image first = shot(Audience::visitor);
  expect_live_frame(first);
  EXPECT_TRUE(view_->exhibit_text().attract);
  EXPECT_EQ(view_->exhibit_text().prompt, "Pick up the handles and squeeze to grab");
  const float* prompt = view_->hud().prompt();
  ASSERT_GT(prompt[2], 200.0F);
  EXPECT_LE(prompt[0] + prompt[2], float(kW)) << "the prompt fits the screen";
  EXPECT_GE(prompt[0], 0.0F);
  EXPECT_GT(prompt[1], 0.6F * kH) << "the prompt sits low, clear of the model";
  EXPECT_GT(text_pixels(first, prompt), int(prompt[2] * prompt[3]) / 100);
  EXPECT_EQ(view_->hud().panel()[2], 0.0F) << "no technical panel for a visitor";
  const glm::vec2 c = model_centre(first, prompt[1]);
  EXPECT_NEAR(c.x, 0.5F * kW, 0.08F * kW) << "the model is centred";
  EXPECT_NEAR(c.y, 0.45F * kH, 0.12F * kH);
  // Two seconds later the model has turned (the camera's azimuth by 24 degrees).
  for (int i = 0; i < 8; ++i) {
    clock_.advance_us(250'000);
    (void)shot(Audience::visitor);
  }
  EXPECT_NEAR(view_->turntable_deg(), 8 * 0.25F * SceneView::kTurntableDegPerS, 0.5F);
  const Image turned = shot(Audience::visitor);
  EXPECT_GT(differing(first.rgba, turned.rgba, 30), 0.01) << "the turntable did not turn";
  // The first grab hands the display over at once: no prompt, the camera given back.
  hands(true);
  const Image grabbed = shot(Audience::visitor);
  EXPECT_FALSE(view_->exhibit_text().attract);
  EXPECT_EQ(view_->turntable_deg(), 0.0F);
  EXPECT_EQ(view_->hud().prompt()[2], 0.0F) << view_->exhibit_text().prompt;
}

TEST_F(ExhibitPictures, TheVisitorViewHasAFewWordsAndNoTechnicalText) {
  status();
  phase(link::VisitorPhase::sculpting);
  hands(false);
  const Image img = shot(Audience::visitor);
  expect_live_frame(img);
  EXPECT_EQ(view_->exhibit_text().prompt, "Grab with both hands");
  const float* prompt = view_->hud().prompt();
  EXPECT_GT(text_pixels(img, prompt), int(prompt[2] * prompt[3]) / 100);
  const float top_left[4] = {0.0F, 0.0F, 0.35F * kW, 0.18F * kH};  // the operator's panel
  EXPECT_EQ(text_pixels(img, top_left), 0) << "technical text in the visitor's view";
  // The idle countdown replaces it near the end.
  phase(link::VisitorPhase::sculpting, 4, 8.0F);
  (void)shot(Audience::visitor);
  EXPECT_EQ(view_->exhibit_text().prompt, "Still there? This sculpture ends in 8 s");
  // And the end of the visit.
  phase(link::VisitorPhase::finished, 4, 0.0F, link::kVisitorResetUndoable, 6.0F);
  const Image saved = shot(Audience::visitor);
  EXPECT_EQ(view_->exhibit_text().prompt, "Your sculpture is saved");
  EXPECT_GT(text_pixels(saved, view_->hud().prompt()), 50);
}

TEST_F(ExhibitPictures, TheOperatorHudHasTheVisitorLineAndNoFrameRateOffscreen) {
  status();
  phase(link::VisitorPhase::sculpting, 5, 75.0F);
  hands(false);
  const Image img = shot(Audience::operator_hud);
  expect_live_frame(img);
  const HudText& text = view_->hud_text();
  for (const std::string& line : text.lines) EXPECT_EQ(line.find("fps"), std::string::npos) << line;
  EXPECT_EQ(text.lines.back(),
            "visitor: sculpting, visitor 12, sculpture 112, 5 strokes, idle left 75 s");
  const float* panel = view_->hud().panel();
  EXPECT_GT(text_pixels(img, panel), int(panel[2] * panel[3]) / 100);
  EXPECT_EQ(view_->hud().prompt()[2], 0.0F) << "no visitor words on the operator's HUD";
}

TEST_F(ExhibitPictures, ANoticeShowsBrieflyWithItsReason) {
  status();
  phase(link::VisitorPhase::sculpting, 2, 60.0F);
  (void)app_->replica().apply(link::Notice{link::NoticeCode::undo_refused, 0});
  const Image img = shot(Audience::visitor);
  ASSERT_EQ(view_->exhibit_text().notices.size(), 1u);
  EXPECT_EQ(view_->exhibit_text().notices[0], "Nothing to undo");
  const float* strip = view_->hud().notices();
  ASSERT_GT(strip[2], 50.0F);
  EXPECT_LT(strip[1], 0.2F * kH) << "notices sit at the top";
  EXPECT_GT(text_pixels(img, strip), int(strip[2] * strip[3]) / 100);
  clock_.advance_us(static_cast<ports::TimestampUs>(ExhibitModel::kNoticeShowS * 1e6));
  (void)shot(Audience::visitor);
  EXPECT_TRUE(view_->exhibit_text().notices.empty());
  EXPECT_EQ(view_->hud().notices()[2], 0.0F);
}

// A command key that does nothing here says why on screen: this rig's display never
// finished a handshake, and a spectator sends no commands at all.
TEST_F(ExhibitPictures, ACommandKeyThatDoesNothingSaysWhy) {
  status();
  phase(link::VisitorPhase::sculpting, 2, 60.0F);
  WindowInput input(*app_, *view_, false);
  EXPECT_FALSE(input.apply(KeyAction::undo));
  const Image img = shot(Audience::visitor);
  ASSERT_EQ(view_->exhibit_text().notices.size(), 1u);
  EXPECT_EQ(view_->exhibit_text().notices[0], "Not connected to the station: the key did nothing");
  EXPECT_GT(text_pixels(img, view_->hud().notices()), 50);
  BridgeOptions spectator;
  spectator.spectator = true;
  BridgeApp watcher(link_, clock_, nullptr, spectator, log_);
  WindowInput watching(watcher, *view_, false);
  EXPECT_FALSE(watching.apply(KeyAction::new_sculpture));
  (void)shot(Audience::visitor);
  ASSERT_EQ(view_->exhibit_text().notices.size(), 2u);
  EXPECT_EQ(view_->exhibit_text().notices[1],
            "This screen only watches: commands come from the sculpting station");
  EXPECT_EQ(watcher.counters().commands_sent, 0u);
}

// The model's silhouette above `below_y`: its bounding box (x0, y0, x1, y1) and mask.
struct Silhouette {
  float box[4] = {1e9F, 1e9F, -1e9F, -1e9F};
  std::vector<bool> mask;
  float width() const { return box[2] - box[0]; }
  float height() const { return box[3] - box[1]; }
};

Silhouette silhouette(const Image& img, float below_y) {
  Silhouette s;
  s.mask.assign(static_cast<std::size_t>(img.width * img.height), false);
  for (int y = 0; y < int(below_y); ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (is_background(img.at(x, y))) continue;
      s.mask[static_cast<std::size_t>(y * img.width + x)] = true;
      s.box[0] = std::min(s.box[0], float(x));
      s.box[1] = std::min(s.box[1], float(y));
      s.box[2] = std::max(s.box[2], float(x));
      s.box[3] = std::max(s.box[3], float(y));
    }
  }
  return s;
}

// Pixels in one silhouette and not the other, over those in either.
double mismatch(const Silhouette& a, const Silhouette& b) {
  double either = 0.0, one = 0.0;
  for (std::size_t i = 0; i < a.mask.size(); ++i) {
    either += (a.mask[i] || b.mask[i]) ? 1.0 : 0.0;
    one += (a.mask[i] != b.mask[i]) ? 1.0 : 0.0;
  }
  return either > 0.0 ? one / either : 0.0;
}

// Attract mode from the station's archive (twister-bridge --attract-archive): between
// visitors the turntable shows the newest archived sculptures in turn, upright and
// where the station's model is, captioned; the first grab shows the station's model
// at once. The archive holds (newest first) a twisted block, a tall column and a wide
// disc. The first picture is the README's exhibit-attract.png.
TEST_F(ExhibitPictures, AttractShowsRecentSculpturesFromTheArchiveUntilTheFirstGrab) {
  test::ShowcaseArchive archive("twister_showcase_image_test");
  const std::string disc = archive.add("20261127T094500", 6, 0.2F, 0.03F, 1);
  const std::string column = archive.add("20261127T101500", 7, 0.03F, 0.2F, 3);
  const std::string twisted = archive.add_twisted("20261127T113000", 8, 4);
  ShowcaseOptions o;
  o.dir = archive.dir.string();
  o.seconds_each = 4.0;
  AttractShowcase showcase(o, log_);
  app_->set_showcase(&showcase);
  view_->options().cues = CueOptions{false, false, false, false, false};  // the models alone
  status();
  phase(link::VisitorPhase::sculpting, 2, 60.0F);
  const Image live = shot(Audience::visitor);
  const float below = 0.6F * kH;  // above the prompt
  const Silhouette live_shape = silhouette(live, below);
  EXPECT_EQ(app_->showing_archive(), "");

  phase(link::VisitorPhase::attract);
  const Image first = shot(Audience::visitor);
  expect_live_frame(first);
  EXPECT_EQ(app_->showing_archive(), twisted);
  EXPECT_EQ(view_->exhibit_text().prompt, "Pick up the handles and squeeze to grab");
  EXPECT_EQ(view_->exhibit_text().detail, "Sculpture 8 \u00b7 4 strokes, by an earlier visitor");
  const float* prompt = view_->hud().prompt();
  EXPECT_GT(prompt[1], below);
  EXPECT_GT(text_pixels(first, prompt), int(prompt[2] * prompt[3]) / 100);
  const Silhouette twisted_shape = silhouette(first, below);
  EXPECT_GT(mismatch(twisted_shape, live_shape), 0.2) << "the archived block, not the live model";
  EXPECT_GT(twisted_shape.height(), 1.2F * twisted_shape.width()) << "it stands upright";
  const glm::vec2 c = model_centre(first, below);
  EXPECT_NEAR(c.x, 0.5F * kW, 0.08F * kW) << "framed where the station's model is";

  // After its seconds the next one, turning: the column, standing up; then the disc.
  const auto wait = [&](double seconds) {
    for (int i = 0; i < int(seconds * 4.0); ++i) {
      clock_.advance_us(250'000);
      (void)shot(Audience::visitor);
    }
    return shot(Audience::visitor);
  };
  const Image second = wait(4.0);
  EXPECT_EQ(app_->showing_archive(), column);
  EXPECT_EQ(view_->exhibit_text().detail, "Sculpture 7 \u00b7 3 strokes, by an earlier visitor");
  const Silhouette column_shape = silhouette(second, below);
  EXPECT_GT(column_shape.height(), 3.0F * column_shape.width()) << "the column stands upright";
  EXPECT_GT(mismatch(column_shape, live_shape), 0.3);
  EXPECT_GT(view_->turntable_deg(), 40.0F);
  const Image third = wait(4.0);
  EXPECT_EQ(app_->showing_archive(), disc);
  const Silhouette disc_shape = silhouette(third, below);
  EXPECT_GT(disc_shape.width(), 1.4F * disc_shape.height()) << "the disc lies flat";
  EXPECT_GT(mismatch(disc_shape, column_shape), 0.5);

  // The first grab: the station's model at once, the camera given back.
  hands(true);
  const Image grabbed = shot(Audience::visitor);
  EXPECT_EQ(app_->showing_archive(), "");
  EXPECT_FALSE(view_->exhibit_text().attract);
  EXPECT_EQ(view_->turntable_deg(), 0.0F);
  EXPECT_LT(mismatch(silhouette(grabbed, below), live_shape), 0.03) << "the live model is back";
}

// No archive (or nothing readable in it): attract turns the station's model as before.
TEST_F(ExhibitPictures, AttractWithoutAnArchiveTurnsTheStationsModel) {
  ShowcaseOptions o;
  o.dir = "/nonexistent/twister/archive";
  AttractShowcase showcase(o, log_);
  app_->set_showcase(&showcase);
  status();
  phase(link::VisitorPhase::sculpting, 2, 60.0F);
  const Image live = shot(Audience::visitor);
  phase(link::VisitorPhase::attract);
  const Image attract = shot(Audience::visitor);
  EXPECT_EQ(app_->showing_archive(), "");
  EXPECT_TRUE(view_->exhibit_text().attract);
  EXPECT_EQ(view_->exhibit_text().detail, "shape the model with both hands");
  EXPECT_LT(mismatch(silhouette(attract, 0.6F * kH), silhouette(live, 0.6F * kH)), 0.03);
}

}  // namespace
}  // namespace twister::bridge::test
