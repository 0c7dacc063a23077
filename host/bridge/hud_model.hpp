// HudModel: the heads-up text of the display, as plain strings (no GL, so it is
// unit-tested on its own; HudRenderer draws it with Dear ImGui):
//   lines: link state, tracker state and rate, each hand, radius, method, clutch,
//          the angle turned against the stroke's limit, mesh size, frames per second;
//   banner: one full-screen message when something needs the sculptor's attention,
//          the most urgent first: "LINK LOST", "TRACKER LOST", "BUTTONS MISSING"
//          (the station's button device is not there), "CAPACITY REACHED",
//          "STROKE NOT SAVED" (for kShowS after the count grows). Capacity is
//          reached when a refined commit was stopped by the mesh's capacity (the
//          status's capacity_stops grew; also kShowS), or when this display
//          refused a mesh above its own limits.
// Station fields the session does not report yet (0 on the wire) show as such.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_replica.hpp"

namespace twister::bridge {

// stopped: the station said goodbye at the end of its run (nothing is wrong here:
// no banner over the model it left).
enum class LinkView : std::uint8_t { waiting, connected, lost, displaced, refused, stopped };

struct HudInput {
  LinkView link = LinkView::waiting;
  bool ready = false;          // the handshake completed (the station's data is trusted)
  double fps = 0.0;            // frames drawn per second (0: not measured, offscreen)
  double now_s = 0.0;          // a monotonic clock, for how long a banner stays
  double hands_rate_hz = 0.0;  // hands updates received per second (< 0: not shown)
  // Attract mode shows a sculpture from the station's archive: its caption ("": the
  // station's model is shown).
  std::string showcase{};
  // The live stroke (one the commit refines) is drawn refined, or not (no GL 4).
  enum class Preview : std::uint8_t { none, refined, unrefined } preview = Preview::none;
};

struct HudText {
  std::vector<std::string> lines;
  std::string banner;  // empty: none
  std::string detail;  // a second line under the banner
};

class HudModel {
 public:
  // How long "capacity reached" and "stroke not saved" stay up after their count grew.
  static constexpr double kShowS = 10.0;
  HudText update(const SceneReplica& replica, const HudInput& input);

 private:
  std::uint64_t not_saved_ = 0;
  double not_saved_since_s_ = -1e9;
  std::uint64_t capacity_stops_ = 0;
  double capacity_since_s_ = -1e9;
};

}  // namespace twister::bridge
