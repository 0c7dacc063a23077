// SceneView: what the sculptor sees in one frame: the mesh (MeshRenderer: weights,
// live warp, smooth shading, at the object pose), the paper's cues over it
// (cue_geometry.hpp, CueRenderer) and the heads-up text (HudModel, HudRenderer)
// for its audience: the operator's technical HUD or the visitor's few words
// (ExhibitModel), with the exhibit's notices over either and, in attract mode, the
// model turning slowly (kTurntableDegPerS) until the first grab.
// BridgeApp draws through it in every mode (window, kiosk, offscreen snapshots).
// Needs a current context. Frame times and the HUD's clock come from the
// ports::Clock it is given.
#pragma once

#include <cstdint>
#include <string>

#include "cue_geometry.hpp"
#include "cue_renderer.hpp"
#include "exhibit_model.hpp"
#include "hud_model.hpp"
#include "hud_renderer.hpp"
#include "mesh_renderer.hpp"
#include "twister/ports/clock.hpp"

namespace twister::bridge {

struct SceneViewOptions {
  CueOptions cues{};
  bool hud = true;
  // Offscreen snapshots: frames are drawn when the link's messages call for a
  // picture, not on a clock, so the HUD shows no frame rate and no per-second
  // hands rate (a picture depends on what arrived, not on when).
  bool offscreen = false;
  // Who the text speaks to (twister-bridge --hud; key Tab switches).
  Audience audience = Audience::operator_hud;
};

class SceneView {
 public:
  // `renderer` and `clock` must outlive the view.
  SceneView(MeshRenderer& renderer, ports::Clock& clock, SceneViewOptions options = {})
      : renderer_(renderer), clock_(clock), options_(options) {}
  // Error not_supported: a shader or the HUD's back end did not start.
  hal::Expected<void> init();
  // One frame of `replica` (already uploaded to the renderer by BridgeApp).
  void draw(const SceneReplica& replica, HudInput input);
  MeshRenderer& renderer() { return renderer_; }
  const CueScene& cues() const { return cues_; }
  const HudText& hud_text() const { return text_; }
  const ExhibitText& exhibit_text() const { return exhibit_text_; }
  // A command key this display refused itself: why, shown like a station's notice.
  void local_notice(std::string text);
  // Attract mode's turntable: degrees of azimuth per second, and how far it has
  // turned the camera now (given back when attract mode ends).
  static constexpr float kTurntableDegPerS = 12.0F;
  float turntable_deg() const { return turned_deg_; }
  const HudRenderer& hud() const { return hud_; }
  SceneViewOptions& options() { return options_; }
  // Frames per second over the last second of draws.
  double fps() const { return fps_; }

 private:
  void turntable(bool on, double delta_s);

  MeshRenderer& renderer_;
  ports::Clock& clock_;
  SceneViewOptions options_;
  CueRenderer cue_renderer_;
  HudRenderer hud_;
  HudModel hud_model_;
  CueScene cues_;
  HudText text_;
  ExhibitModel exhibit_;
  ExhibitText exhibit_text_;
  float turned_deg_ = 0.0F;         // the turntable's turn of the camera
  bool drawn_ = false;              // a frame was drawn (last_us_ holds its time)
  ports::TimestampUs last_us_ = 0;  // the last frame's time
  ports::TimestampUs second_start_us_ = 0;
  int frames_in_second_ = 0;
  double fps_ = 0.0;
};

}  // namespace twister::bridge
