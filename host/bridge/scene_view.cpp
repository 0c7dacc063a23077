#include "scene_view.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace twister::bridge {

hal::Expected<void> SceneView::init() {
  if (hal::Expected<void> cues = cue_renderer_.init(); !cues) return cues;
  if (options_.hud) return hud_.init(renderer_.height());
  return {};
}

void SceneView::local_notice(std::string text) {
  exhibit_.local_notice(std::move(text), 1e-6 * static_cast<double>(clock_.now_us()));
}

void SceneView::turntable(bool on, double delta_s) {
  Camera& camera = renderer_.camera();
  if (on) {
    const float step = kTurntableDegPerS * static_cast<float>(std::min(delta_s, 0.25));
    camera.orbit(step, 0.0F);
    turned_deg_ = std::fmod(turned_deg_ + step, 360.0F);
  } else if (turned_deg_ != 0.0F) {
    camera.orbit(-turned_deg_, 0.0F);  // the visitor's view is the one before attract
    turned_deg_ = 0.0F;
  }
}

void SceneView::draw(const SceneReplica& replica, HudInput input) {
  const ports::TimestampUs now_us = clock_.now_us();
  const double delta = drawn_ ? 1e-6 * static_cast<double>(now_us - last_us_) : 1.0 / 60.0;
  drawn_ = true;
  last_us_ = now_us;
  ++frames_in_second_;
  const double window = 1e-6 * static_cast<double>(now_us - second_start_us_);
  if (window >= 1.0) {
    fps_ = static_cast<double>(frames_in_second_) / window;
    frames_in_second_ = 0;
    second_start_us_ = now_us;
  }
  input.now_s = 1e-6 * static_cast<double>(now_us);
  if (options_.offscreen) input.hands_rate_hz = -1.0;
  exhibit_text_ = exhibit_.update(replica, input, options_.audience);
  turntable(exhibit_text_.attract, delta);
  renderer_.begin_frame();
  if (replica.has_mesh()) renderer_.draw_mesh();
  const Camera& camera = renderer_.camera();
  build_cues(replica, renderer_.model_matrix(), renderer_.model_radius(), options_.cues, cues_);
  cue_renderer_.draw(
      cues_, camera.projection(renderer_.width(), renderer_.height()) * camera.view_matrix());
  if (options_.hud) {
    input.fps = options_.offscreen ? 0.0 : fps_;
    if (replica.live().active && replica.live().refine_threshold_m > 0.0 &&
        !replica.live().cpu_path()) {
      input.preview =
          renderer_.refining_live() ? HudInput::Preview::refined : HudInput::Preview::unrefined;
    }
    text_ = hud_model_.update(replica, input);
    if (options_.audience == Audience::operator_hud) {
      if (std::string line = visitor_line(replica); !line.empty())
        text_.lines.push_back(std::move(line));
    } else {
      text_ = HudText{};  // the visitor reads the exhibit's words alone
    }
    hud_.draw(text_, renderer_.width(), renderer_.height(), delta, exhibit_text_);
  }
  renderer_.end_frame();
}

}  // namespace twister::bridge
