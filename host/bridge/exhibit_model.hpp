// ExhibitModel: the display's words for the exhibit (issue 25), as plain strings (no
// GL, unit-tested on its own; HudRenderer draws them):
//   - two audiences: the visitor view (the default in kiosk mode) shows the model,
//     the hands and their cues and a few friendly words for the states that matter
//     ("Grab with both hands", "Tracker lost, please wait", a countdown when idle
//     is about to end the sculpture, "Your sculpture is saved"); the operator's
//     view is the technical HUD (HudModel) with the visitor line added;
//   - attract mode: while the station's visitor phase is attract and no hand grabs,
//     the display turns the model slowly and invites ("Pick up the handles and
//     squeeze to grab"); the first grab (or the phase turning to sculpting) ends it
//     at once;
//   - notices: each link::Notice the station sends, and each command key this
//     display refused itself (not admitted, a spectator, nothing to bring back),
//     shows for kNoticeShowS as a short sentence saying why nothing happened or
//     what just did, in both views.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "hud_model.hpp"
#include "scene_replica.hpp"

namespace twister::bridge {

// Who the screen speaks to (twister-bridge --hud visitor|operator, key Tab).
enum class Audience : std::uint8_t { visitor, operator_hud };

struct ExhibitText {
  std::string prompt;                // large friendly words, lower middle ("": none)
  std::string detail;                // a smaller line under the prompt
  std::vector<std::string> notices;  // shown now, oldest first
  bool attract = false;              // attract mode: the turntable turns
};

class ExhibitModel {
 public:
  static constexpr double kNoticeShowS = 2.5;  // how long a notice stays up
  static constexpr float kCountdownS = 15.0F;  // idle time left below which it counts down
  static constexpr std::size_t kNoticesShown = 3;
  ExhibitText update(const SceneReplica& replica, const HudInput& input, Audience audience);
  // A command key this display refused itself: shown like a station's notice.
  void local_notice(std::string text, double now_s);

 private:
  struct Shown {
    std::string text;
    double since_s = 0.0;
  };
  std::uint64_t notices_seen_ = 0;  // replica notices already taken
  std::deque<Shown> shown_;
};

// The sentence a visitor reads for a station notice (operator: the same, prefixed
// with the code's name).
std::string notice_sentence(link::NoticeCode code);
// The same, told more precisely by the notice's detail where the station gives one (a
// refused undo / redo / command / press: the session's input::Reason).
std::string notice_sentence(link::NoticeCode code, std::uint8_t detail);
std::string notice_name(link::NoticeCode code);
// The operator HUD's visitor line ("" without a visitor state).
std::string visitor_line(const SceneReplica& replica);
// Attract mode: a visitor state in phase attract and no hand grabbing.
bool attract_mode(const SceneReplica& replica);

}  // namespace twister::bridge
