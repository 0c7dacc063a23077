#include "bridge_app.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <span>

#include "attract_showcase.hpp"
#include "cue_geometry.hpp"
#include "exhibit_model.hpp"
#include "scene_view.hpp"

namespace twister::bridge {

using ports::LogLevel;

BridgeApp::BridgeApp(ports::LinkPort& port, ports::Clock& clock, MeshRenderer* renderer,
                     BridgeOptions options, ports::LogSink& log)
    : port_(port),
      clock_(clock),
      renderer_(renderer),
      log_(log),
      options_(std::move(options)),
      replica_(options_.limits),
      in_(std::size_t{64} * 1024) {}

std::size_t BridgeApp::step() {
  if (stop_ != BridgeStop::none) return 0;  // backed off: the link is left alone
  if (yield_.active && now_ms() < yield_.retry_at_ms) return 0;  // displaced: not yet
  std::size_t frames = 0;
  for (int round = 0; round < 64 && stop_ == BridgeStop::none; ++round) {
    const Result<std::size_t> got = port_.receive(in_);
    if (!got.ok()) {
      if (connected_) {
        ++counters_.disconnects;
        log_.write(LogLevel::warning, "link", "lost; reconnecting");
      }
      connected_ = false;
      ready_ = false;
      out_.clear();
      return frames;
    }
    if (!connected_) on_connect();
    for (std::size_t i = 0; i < *got && stop_ == BridgeStop::none; ++i) {
      if (const auto m = decoder_.process(in_[i]); m.ok()) {
        handle(**m);
        ++frames;
      }
    }
    if (decoder_.other_version() != 0 && stop_ == BridgeStop::none) {
      log_.write(LogLevel::error, "link",
                 "the station speaks link protocol %u, this bridge %u; refusing it",
                 {static_cast<unsigned>(decoder_.other_version()),
                  static_cast<unsigned>(link::kProtocolVersion)});
      stop(BridgeStop::version);
    }
    if (*got < in_.size()) break;
  }
  if (connected_ && stop_ == BridgeStop::none) keep_alive();
  flush();
  refresh_display();
  return frames;
}

void BridgeApp::handle(const link::LinkMessage& m) {
  last_frame_ms_ = now_ms();
  if (std::holds_alternative<link::Hands>(m)) {
    const std::int64_t second = last_frame_ms_ / 1000;
    if (second != hands_second_) {
      hands_last_second_ = second == hands_second_ + 1 ? hands_in_second_ : 0;
      hands_second_ = second;
      hands_in_second_ = 0;
    }
    counters_.hands_busiest_second = std::max(counters_.hands_busiest_second, ++hands_in_second_);
  }
  if (const auto* hello = std::get_if<link::Hello>(&m)) {
    on_station_hello(*hello);
    return;
  }
  if (const auto* auth = std::get_if<link::Auth>(&m)) {
    on_station_auth(*auth);
    return;
  }
  if (const auto* bye = std::get_if<link::Bye>(&m)) {
    on_bye(*bye);
    return;
  }
  if (!ready_) {
    ++counters_.ignored;  // not trusted before the handshake completes
    return;
  }
  handle_scene(m);
}

void BridgeApp::handle_scene(const link::LinkMessage& m) {
  // The live warp as the stroke ends (the hands leave it, or its commit arrives) is
  // the stroke's final preview: picture it before the message ends it.
  const LiveState& live = replica_.live();
  const auto* begin = std::get_if<link::MeshBegin>(&m);
  const auto* hands = std::get_if<link::Hands>(&m);
  const bool ends_live =
      (begin != nullptr && !begin->full) ||
      (hands != nullptr && ((hands->flags & link::kStrokeActive) == 0 ||
                            hands->stroke != static_cast<std::uint16_t>(live.stroke)));
  if (ends_live && live.active && live.stroke != live_pictured_ && !options_.snapshot_dir.empty()) {
    refresh_display();
    const std::string path = snapshot("live-" + std::to_string(replica_.version() + 1));
    if (!path.empty()) write_cues(path.substr(0, path.size() - 4) + ".cues");
    live_pictured_ = live.stroke;
  }
  const std::uint64_t commits = replica_.counters().commits;
  const std::uint64_t fulls = replica_.counters().full_meshes;
  if (const auto request = replica_.apply(m)) {
    send(*request);
    log_.write(LogLevel::warning, "replica",
               "mesh change set rejected (checksum/version); asked for a full resend");
  }
  if (replica_.counters().over_capacity != over_capacity_logged_) {
    over_capacity_logged_ = replica_.counters().over_capacity;
    log_.write(
        LogLevel::error, "replica",
        "mesh of %u vertices, %u triangles refused: above the limits (%u, %u)",
        {begin != nullptr ? begin->vertex_count : 0U, begin != nullptr ? begin->triangle_count : 0U,
         replica_.limits().max_vertices, replica_.limits().max_triangles});
  }
  if (replica_.counters().full_meshes != fulls) {
    log_.write(
        LogLevel::notice, "replica", "mesh version %u: %zu vertices, %zu triangles",
        {replica_.version(), replica_.mesh().vertex_count(), replica_.mesh().triangle_count()});
    // A later full mesh is a new model too (a resync, or a commit the link could not
    // send as a change set, such as one that refined the mesh).
    if (!options_.snapshot_dir.empty()) {
      refresh_display();
      snapshot(fulls == 0 ? std::string("rest") : "mesh-" + std::to_string(replica_.version()));
    }
  }
  if (replica_.counters().commits != commits) {
    log_.write(LogLevel::notice, "replica", "commit -> mesh version %u, checksum %016llx verified",
               {replica_.version(), replica_.checksum()});
    if (!options_.snapshot_dir.empty()) {
      refresh_display();
      snapshot("commit-" + std::to_string(replica_.version()));
    }
  }
  if (hands != nullptr) follow_cursors();
  if (hands != nullptr && options_.movie_every > 0 && !options_.snapshot_dir.empty() &&
      ++movie_hands_ % options_.movie_every == 0) {
    refresh_display();
    std::array<char, 16> name{};
    std::snprintf(name.data(), name.size(), "frame-%05llu",
                  static_cast<unsigned long long>(++movie_frames_));
    const std::string path = snapshot(name.data());
    if (!path.empty()) write_cues(path.substr(0, path.size() - 4) + ".cues");
  }
}

bool BridgeApp::send_command(const link::Command& command) {
  if (!ready() || options_.spectator) return false;
  send(command);
  flush();
  ++counters_.commands_sent;
  return true;
}

void BridgeApp::flush() {
  while (!out_.empty()) {
    const auto n = port_.send(out_);
    if (!n.ok() || *n == 0) return;
    out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(*n));
  }
}

bool BridgeApp::show_archive() {
  const bool attract = showcase_ != nullptr && attract_mode(replica_);
  const double now_s = 1e-6 * static_cast<double>(clock_.now_us());
  if (attract && !in_attract_) showcase_->begin(now_s);
  in_attract_ = attract;
  const ShowcaseModel* model = attract ? showcase_->at(now_s) : nullptr;
  if (model == nullptr) {
    if (showing_serial_ != 0) {  // the first grab: the station's model at once
      showing_serial_ = 0;
      showing_name_.clear();
      showing_caption_.clear();
      live_mesh_stale_ = true;
    }
    return false;
  }
  renderer_->set_object_pose(replica_.object_pose());
  if (model->serial != showing_serial_) {
    // Upright (its +Y along the world's up, seen in the object frame) and where the
    // station's model is, within its bounding sphere: the camera's framing holds it.
    const glm::vec3 up = glm::normalize(glm::vec3(glm::inverse(renderer_->model_matrix()) *
                                                  glm::vec4(renderer_->camera().up(), 0.0F)));
    // Three quarters of the framed sphere: a slender sculpture (whose half diagonal is
    // nearly its half height) stays clear of the screen's edge and the invitation.
    constexpr float kFill = 0.75F;
    renderer_->set_mesh(place_upright(model->mesh, up, renderer_->model_centre(),
                                      kFill * renderer_->model_radius()),
                        true);
    if (showing_serial_ == 0)
      log_.write(LogLevel::info, "attract", "showing the archive's %s", {model->name.c_str()});
    showing_serial_ = model->serial;
    showing_name_ = model->name;
    showing_caption_ = model->caption;
  }
  renderer_->set_show_weights(false);
  renderer_->set_live(nullptr);
  return true;
}

void BridgeApp::refresh_display() {
  if (renderer_ == nullptr || !replica_.has_mesh()) return;
  if (shown_version_ != 0 && show_archive()) return;
  LiveState& live = replica_.live();
  const bool cpu_live = live.active && !renderer_->warps_on_gpu(live);
  renderer_->set_object_pose(replica_.object_pose());
  bool uploaded = false;
  if (replica_.mesh_changed() || (display_mesh_live_ && !cpu_live) || live_mesh_stale_) {
    live_mesh_stale_ = false;
    const bool first = shown_version_ == 0;
    renderer_->set_mesh(replica_.mesh(), replica_.shading(), !first);
    replica_.clear_mesh_changed();
    shown_version_ = replica_.version();
    display_mesh_live_ = false;
    uploaded = true;
  }
  refresh_weights(uploaded);
  const std::uint64_t live_frames = replica_.counters().live_frames;
  if (cpu_live && (!display_mesh_live_ || live_frames != shown_live_frames_)) {
    // scodef has no closed form per vertex in the shader: show the CPU warp, once per
    // live frame. The renderer already holds this mesh's triangles and this stroke's
    // weights, so only the positions (and their normals) change.
    const MeshData warped = replica_.cpu_warp();
    if (warped.vertex_count() == renderer_->vertex_count()) {
      renderer_->set_positions(warped);
    } else {  // no warp (the plan failed: nothing drawn), or the first one after that
      renderer_->set_mesh(warped, true);
      showing_live_weights_ = false;
      refresh_weights(true);
    }
    display_mesh_live_ = true;
    shown_live_frames_ = live_frames;
  }
  renderer_->set_show_weights(live.active || preview_.hand_mask() != 0);
  renderer_->set_live(live.active ? &live : nullptr);
  hold_framing();
}

bool BridgeApp::workspace_framing() const {
  if (renderer_ == nullptr || !replica_.has_mesh() || !replica_.has_workspace() ||
      shown_version_ == 0) {
    return false;
  }
  switch (options_.framing) {
    case Framing::model:
      return false;
    case Framing::workspace:
      return true;
    case Framing::automatic:
      break;
  }
  return (replica_.workspace().flags & (link::kWorkspaceCalibrated | link::kWorkspaceConfigured)) !=
         0;
}

void BridgeApp::hold_framing() {
  if (!workspace_framing()) return;
  const link::Workspace& w = replica_.workspace();
  const Sphere before = framing_.sphere();
  const bool was_active = framing_.active();
  const Sphere model{
      glm::vec3(renderer_->model_matrix() * glm::vec4(renderer_->model_centre(), 1.0F)),
      renderer_->model_radius()};
  framing_.hold(w.min, w.max, model);
  Camera& camera = renderer_->camera();
  if (!was_active) {
    camera.set_up(w.up);
    log_.write(LogLevel::info, "camera",
               "framing the station's working volume (%s) and the model: centre (%.3f, %.3f, "
               "%.3f) m, radius %.3f m, up (%.0f, %.0f, %.0f)",
               {(w.flags & link::kWorkspaceConfigured) != 0   ? "configured"
                : (w.flags & link::kWorkspaceCalibrated) != 0 ? "above the work frame's origin"
                                                              : "the tracker's range",
                static_cast<double>(framing_.sphere().centre.x),
                static_cast<double>(framing_.sphere().centre.y),
                static_cast<double>(framing_.sphere().centre.z),
                static_cast<double>(framing_.sphere().radius), static_cast<double>(w.up.x),
                static_cast<double>(w.up.y), static_cast<double>(w.up.z)});
  }
  const Sphere& now = framing_.sphere();
  if (!was_active || now.radius != before.radius || now.centre != before.centre) {
    camera.frame(now.centre, now.radius);
  }
}

void BridgeApp::follow_cursors() {
  hold_framing();
  if (!framing_.active() || !workspace_framing()) return;
  std::array<glm::vec3, link::kLinkHands> cursors{};
  std::size_t n = 0;
  for (const HandView& v : replica_.hands()) {
    if (!v.present || n == cursors.size()) continue;
    cursors[n++] = glm::vec3(renderer_->model_matrix() * glm::vec4(glm::vec3(v.pose.origin), 1.0F));
  }
  if (framing_.follow(std::span<const glm::vec3>(cursors.data(), n))) {
    renderer_->camera().frame(framing_.sphere().centre, framing_.sphere().radius);
    log_.write(LogLevel::debug, "camera", "framing grows to keep the cursors: radius %.3f m",
               {static_cast<double>(framing_.sphere().radius)});
  }
}

void BridgeApp::refresh_weights(bool mesh_uploaded) {
  LiveState& live = replica_.live();
  if (live.active) {
    // The stroke's weights (plan order) in the colours of its session hands.
    if (mesh_uploaded || !showing_live_weights_ || live.weights_changed ||
        live.stroke != shown_stroke_) {
      renderer_->set_weights(
          live.weight1, live.weight2,
          {live.hands.empty() ? std::uint8_t{0} : live.hands[0].session_hand,
           live.hands.size() > 1 ? live.hands[1].session_hand : std::uint8_t{1}});
      renderer_->set_gradients(live.gradient1, live.gradient2);
      live.weights_changed = false;
      shown_stroke_ = live.stroke;
      showing_live_weights_ = true;
    }
    return;
  }
  // Before a grab: what each hand would grab now, as the station would weigh it.
  const bool rebuilt =
      preview_.update(replica_.mesh(), replica_.version(), replica_.hands(), replica_.radius_m());
  if (rebuilt || mesh_uploaded || showing_live_weights_) {
    renderer_->set_weights(preview_.hand1(), preview_.hand2(), {0, 1});
    renderer_->set_gradients({}, {});
    showing_live_weights_ = false;
  }
}

LinkView BridgeApp::link_view() const {
  if (yield_.active) return LinkView::displaced;
  switch (stop_) {
    case BridgeStop::unauthorised:
    case BridgeStop::version:
      return LinkView::refused;
    case BridgeStop::none:
      break;
  }
  if (connected_) return LinkView::connected;
  if (station_stopped_) return LinkView::stopped;
  return counters_.connects > 0 ? LinkView::lost : LinkView::waiting;
}

HudInput BridgeApp::hud_input() const {
  HudInput in;
  in.link = link_view();
  in.ready = ready();
  const std::int64_t now_s = now_ms() / 1000;
  in.showcase = showing_caption_;
  in.hands_rate_hz = static_cast<double>(now_s == hands_second_       ? hands_last_second_
                                         : now_s == hands_second_ + 1 ? hands_in_second_
                                                                      : 0);
  return in;
}

void BridgeApp::draw() {
  if (view_ != nullptr) {
    view_->draw(replica_, hud_input());
  } else if (renderer_ != nullptr) {
    renderer_->draw();
  }
}

void BridgeApp::write_cues(const std::string& path) const {
  // Where the picture's cues are (pixels, top-left origin), for checks of the
  // picture that need no GL: sim/scenarios/picture_check.py --cues; and the camera
  // (size, view-projection matrix, column-major) to project any world point.
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return;
  const Camera& camera = renderer_->camera();
  const int w = renderer_->width();
  const int h = renderer_->height();
  std::fprintf(f,
               "# %s: the screw axes (axis x0 y0 x1 y1), hand cursors (cursor x y),\n"
               "# the HUD panel (panel x y w h); pixels, top-left origin\n",
               path.c_str());
  for (const auto& [from, to] :
       drawn_screw_axes(replica_, renderer_->model_matrix(), renderer_->model_radius())) {
    const auto a = camera.project(from, w, h);
    const auto b = camera.project(to, w, h);
    if (a && b) std::fprintf(f, "axis %.1f %.1f %.1f %.1f\n", a->x, a->y, b->x, b->y);
  }
  for (const HandView& v : replica_.hands()) {
    if (!v.present) continue;
    const glm::vec3 world(renderer_->model_matrix() * glm::vec4(glm::vec3(v.pose.origin), 1.0F));
    if (const auto p = camera.project(world, w, h))
      std::fprintf(f, "cursor %.1f %.1f\n", p->x, p->y);
  }
  if (view_ != nullptr) {
    const float* r = view_->hud().panel();
    std::fprintf(f, "panel %.1f %.1f %.1f %.1f\n", r[0], r[1], r[2], r[3]);
  }
  std::fprintf(f, "size %d %d\n", w, h);
  const glm::mat4 vp = camera.projection(w, h) * camera.view_matrix();
  std::fprintf(f, "viewproj");
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) std::fprintf(f, " %.7g", static_cast<double>(vp[c][r]));
  }
  std::fprintf(f, "\n");
  std::fclose(f);
}

std::string BridgeApp::snapshot(const std::string& name) {
  if (renderer_ == nullptr || options_.snapshot_dir.empty()) return {};
  draw();
  std::string path = options_.snapshot_dir + "/" + name + ".png";
  if (const hal::Expected<void> written =
          write_png(path, renderer_->width(), renderer_->height(), renderer_->read_rgba());
      !written) {
    log_.write(LogLevel::error, "snapshot", "%s", {written.error().message.c_str()});
    return {};
  }
  ++counters_.snapshots;
  pictures_.push_back(path);
  log_.write(LogLevel::info, "snapshot", "wrote %s", {path.c_str()});
  return path;
}

}  // namespace twister::bridge
