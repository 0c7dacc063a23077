#include "hud_model.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <numbers>

namespace twister::bridge {
namespace {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buffer[256];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

const char* link_text(LinkView link) {
  switch (link) {
    case LinkView::waiting:
      return "waiting for the station";
    case LinkView::connected:
      return "connected";
    case LinkView::lost:
      return "lost, reconnecting";
    case LinkView::displaced:
      return "another display has the link (retrying)";
    case LinkView::refused:
      return "refused by the station";
    case LinkView::stopped:
      return "the station stopped (end of its run)";
  }
  return "?";
}

std::string hand_line(std::size_t h, const HandView& v) {
  if (!v.present) return format("hand %zu: %s", h + 1, v.tracked ? "tracked" : "not tracked");
  const glm::dvec3 p = v.pose.origin;
  return format("hand %zu: %s (%+.3f %+.3f %+.3f) m%s%s%s%s", h + 1, v.tracked ? "tracked" : "held",
                p.x, p.y, p.z, v.grab ? "  grab" : "", v.in_stroke ? " (stroke)" : "",
                v.freeze ? "  clutch" : "", v.move_object ? "  move" : "");
}

bool full(const link::StatusReport& s) {
  return (s.vertex_capacity > 0 && s.vertex_count >= s.vertex_capacity) ||
         (s.triangle_capacity > 0 && s.triangle_count >= s.triangle_capacity);
}

// The angle turned in the open stroke: the live screws follow the hands at the
// tracker rate (past a half turn too); the status's copy comes once a second.
double turned_rad(const SceneReplica& r, const link::StatusReport& s) {
  const LiveState& live = r.live();
  if (!live.active) return s.turned_rad;
  double most = 0.0;
  for (const LiveHand& hand : live.hands) most = std::max(most, hand.screw.angle);
  return most;
}

bool buttons_missing(const link::StatusReport& s) {
  return s.buttons_state == static_cast<std::uint8_t>(link::ButtonsState::missing);
}

void station_lines(const SceneReplica& r, std::vector<std::string>& lines) {
  if (!r.has_status()) {
    lines.emplace_back("tracker: no status yet");
    return;
  }
  const link::StatusReport& s = r.station_status();
  const char* state = s.tracker_state == 1   ? "streaming"
                      : s.tracker_state == 2 ? "LOST"
                                             : "starting";
  lines.push_back(format("tracker: %s, %.0f poses/s   buttons: %s", state,
                         static_cast<double>(s.tracker_rate_hz),
                         buttons_missing(s) ? "MISSING" : "present"));
  const double turned = turned_rad(r, s);
  const std::string turn =
      s.turn_limit_rad > 0.0F
          ? format("%.0f of %.0f deg", degrees(turned), degrees(s.turn_limit_rad))
          : format("%.0f deg (no limit reported)", degrees(turned));
  lines.push_back(
      format("method: %s   clutch: %s%s%s   turn: %s",
             std::string(math::warp_method_name(static_cast<math::WarpMethod>(s.method))).c_str(),
             s.clutch == 0 ? "off" : "", (s.clutch & 1) != 0 ? "hand 1 " : "",
             (s.clutch & 2) != 0 ? "hand 2" : "", turn.c_str()));
  lines.push_back(format(
      "mesh: v%u, %u / %u vertices, %u / %u triangles%s; strokes %llu "
      "(%llu not saved)",
      s.mesh_version, s.vertex_count, s.vertex_capacity, s.triangle_count, s.triangle_capacity,
      full(s) ? " (full)" : "", static_cast<unsigned long long>(s.strokes.committed),
      static_cast<unsigned long long>(s.strokes.not_saved)));
}

}  // namespace

HudText HudModel::update(const SceneReplica& r, const HudInput& in) {
  HudText out;
  const char* handshake = in.link == LinkView::connected && !in.ready ? " (handshake)" : "";
  const auto missed = static_cast<unsigned long long>(r.counters().live_missed);
  out.lines.push_back(
      in.hands_rate_hz >= 0.0
          ? format("link: %s%s, hands %.0f/s, missed %llu", link_text(in.link), handshake,
                   in.hands_rate_hz, missed)
          : format("link: %s%s, hands missed %llu", link_text(in.link), handshake, missed));
  station_lines(r, out.lines);
  for (std::size_t h = 0; h < r.hands().size(); ++h)
    out.lines.push_back(hand_line(h, r.hands()[h]));
  out.lines.push_back(format("radius: %.3f m", static_cast<double>(r.radius_m())));
  out.lines.push_back(in.fps >= 0.1  // offscreen runs in virtual time have no frame rate
                          ? format("display: %zu vertices, %zu triangles, %.1f fps",
                                   r.mesh().vertex_count(), r.mesh().triangle_count(), in.fps)
                          : format("display: %zu vertices, %zu triangles", r.mesh().vertex_count(),
                                   r.mesh().triangle_count()));
  if (in.preview != HudInput::Preview::none) {
    const double mm = 1e3 * r.live().refine_threshold_m;
    out.lines.push_back(in.preview == HudInput::Preview::refined
                            ? format("live preview: refined to %.2f mm as the commit will be", mm)
                            : format("live preview: unrefined (needs OpenGL 4); the commit "
                                     "refines to %.2f mm",
                                     mm));
  }
  // Capacity reached: a refined commit was stopped by the mesh's capacity (for
  // kShowS after the count grows), or this display refused a mesh above its limits.
  const std::uint64_t stops = r.has_status() ? r.station_status().strokes.capacity_stops : 0;
  if (stops > capacity_stops_) capacity_since_s_ = in.now_s;
  capacity_stops_ = stops;
  const bool capacity =
      (stops > 0 && in.now_s - capacity_since_s_ < kShowS) || r.counters().over_capacity > 0;
  const std::uint64_t not_saved = r.has_status() ? r.station_status().strokes.not_saved : 0;
  if (not_saved > not_saved_) not_saved_since_s_ = in.now_s;
  not_saved_ = not_saved;
  if (in.link == LinkView::lost || in.link == LinkView::displaced || in.link == LinkView::refused) {
    out.banner = in.link == LinkView::lost ? "LINK LOST" : "NO LINK";
    out.detail = format("the station is not reachable: %s", link_text(in.link));
  } else if (r.has_status() && r.station_status().tracker_state == 2) {
    out.banner = "TRACKER LOST";
    out.detail = "no valid poses: check the tracker's cable and power";
  } else if (r.has_status() && buttons_missing(r.station_status())) {
    out.banner = "BUTTONS MISSING";
    out.detail = "the button device is not there: plug it in; the station picks it up";
  } else if (capacity) {
    out.banner = "CAPACITY REACHED";
    out.detail = r.counters().over_capacity > 0
                     ? "the station's mesh is larger than this display accepts (--max-vertices)"
                     : "the mesh is full: strokes are no longer refined";
  } else if (not_saved > 0 && in.now_s - not_saved_since_s_ < kShowS) {
    out.banner = "STROKE NOT SAVED";
    out.detail = format("%llu stroke(s) not written to the journal",
                        static_cast<unsigned long long>(not_saved));
  }
  return out;
}

}  // namespace twister::bridge
