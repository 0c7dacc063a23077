#include "scene_view.hpp"

namespace twister::bridge {

hal::Expected<void> SceneView::init() {
  if (hal::Expected<void> cues = cue_renderer_.init(); !cues) return cues;
  if (options_.hud) return hud_.init(renderer_.height());
  return {};
}

void SceneView::draw(const SceneReplica& replica, HudInput input) {
  const auto now = std::chrono::steady_clock::now();
  const double delta = last_.time_since_epoch().count() == 0
                           ? 1.0 / 60.0
                           : std::chrono::duration<double>(now - last_).count();
  last_ = now;
  ++frames_in_second_;
  const double window = std::chrono::duration<double>(now - second_start_).count();
  if (window >= 1.0) {
    fps_ = static_cast<double>(frames_in_second_) / window;
    frames_in_second_ = 0;
    second_start_ = now;
  }
  renderer_.begin_frame();
  if (replica.has_mesh()) renderer_.draw_mesh();
  const Camera& camera = renderer_.camera();
  build_cues(replica, renderer_.model_matrix(), renderer_.model_radius(), options_.cues, cues_);
  cue_renderer_.draw(
      cues_, camera.projection(renderer_.width(), renderer_.height()) * camera.view_matrix());
  if (options_.hud) {
    input.fps = fps_;
    input.now_s = std::chrono::duration<double>(now.time_since_epoch()).count();
    text_ = hud_model_.update(replica, input);
    hud_.draw(text_, renderer_.width(), renderer_.height(), delta);
  }
  renderer_.end_frame();
}

}  // namespace twister::bridge
