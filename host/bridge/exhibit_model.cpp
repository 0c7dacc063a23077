#include "exhibit_model.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "twister/input/interaction_machine.hpp"

namespace twister::bridge {
namespace {

bool any_grab(const SceneReplica& r) {
  for (const HandView& h : r.hands()) {
    if (h.grab || h.in_stroke) return true;
  }
  return r.live().active;
}

bool tracker_lost(const SceneReplica& r) {
  return r.has_status() &&
         r.station_status().tracker_state == static_cast<std::uint8_t>(link::TrackerState::lost);
}

bool buttons_missing(const SceneReplica& r) {
  return r.has_status() &&
         r.station_status().buttons_state == static_cast<std::uint8_t>(link::ButtonsState::missing);
}

const char* phase_name(link::VisitorPhase p) {
  switch (p) {
    case link::VisitorPhase::attract:
      return "attract";
    case link::VisitorPhase::sculpting:
      return "sculpting";
    case link::VisitorPhase::finished:
      return "finished";
  }
  return "?";
}

// Whole seconds left, rounded up (a countdown never shows 0 while time is left).
int seconds_left(float s) { return static_cast<int>(std::ceil(static_cast<double>(s))); }

// The visitor's words for the state that matters most now.
void visitor_words(const SceneReplica& r, const HudInput& in, ExhibitText& out) {
  if (in.link != LinkView::connected || !in.ready) {
    out.prompt = "One moment, please";
    out.detail = "the screen is reaching the sculpting station";
    return;
  }
  if (tracker_lost(r)) {
    out.prompt = "Tracker lost, please wait";
    out.detail = "your sculpture is safe; it comes back by itself";
    return;
  }
  if (buttons_missing(r)) {
    out.prompt = "The handles are not ready";
    out.detail = "please wait or ask a member of staff";
    return;
  }
  const bool exhibit = r.has_visitor();
  const link::VisitorState& v = r.visitor();
  if (exhibit && v.phase == link::VisitorPhase::finished) {
    const bool saved = (v.flags & link::kVisitorArchiveFailed) == 0;
    out.prompt = saved ? "Your sculpture is saved" : "Thank you for sculpting!";
    char detail[160];
    if ((v.flags & link::kVisitorResetUndoable) != 0 && v.grace_left_s > 0.0F) {
      std::snprintf(detail, sizeof detail, "changed your mind? press U within %d s to keep going",
                    seconds_left(v.grace_left_s));
    } else if (saved) {
      std::snprintf(detail, sizeof detail, "sculpture %u, %u stroke%s: thank you!", v.sculpture,
                    v.strokes, v.strokes == 1 ? "" : "s");
    } else {
      std::snprintf(detail, sizeof detail, "(it could not be kept this time)");
    }
    out.detail = detail;
    return;
  }
  if (exhibit && v.phase == link::VisitorPhase::attract && !any_grab(r)) {
    out.attract = true;
    out.prompt = "Pick up the handles and squeeze to grab";
    out.detail = in.showcase.empty() ? std::string("shape the model with both hands")
                                     : in.showcase + ", by an earlier visitor";
    return;
  }
  if (exhibit && v.idle_left_s > 0.0F && v.idle_left_s <= ExhibitModel::kCountdownS) {
    char prompt[96];
    std::snprintf(prompt, sizeof prompt, "Still there? This sculpture ends in %d s",
                  seconds_left(v.idle_left_s));
    out.prompt = prompt;
    out.detail = "move a handle to keep sculpting";
    return;
  }
  const std::uint64_t strokes = exhibit          ? v.strokes
                                : r.has_status() ? r.station_status().strokes.committed
                                                 : 0;
  if (strokes == 0 && !any_grab(r)) {
    out.prompt = "Grab with both hands";
    out.detail = "squeeze the handles near the model and pull, push or twist";
  }
}

}  // namespace

std::string notice_sentence(link::NoticeCode code) {
  switch (code) {
    case link::NoticeCode::undo_refused:
      return "Nothing to undo";
    case link::NoticeCode::redo_refused:
      return "Nothing to redo";
    case link::NoticeCode::command_refused_spectator:
      return "This screen only watches: commands come from the sculpting station";
    case link::NoticeCode::nothing_to_act_on:
      return "Nothing to grab there: bring a handle to the model";
    case link::NoticeCode::sculpture_archived:
      return "Your sculpture is saved";
    case link::NoticeCode::archive_failed:
      return "The sculpture could not be saved";
    case link::NoticeCode::disk_full:
      return "The archive is full: sculpting goes on";
    case link::NoticeCode::new_sculpture_undone:
      return "Your sculpture is back";
    case link::NoticeCode::symmetry_changed:
      return "Mirroring changed for the next stroke";
  }
  return "The station says something this display does not know";
}

std::string notice_sentence(link::NoticeCode code, std::uint8_t detail) {
  // The station's detail for a refusal is the session's reason (input::Reason).
  const auto reason = static_cast<input::Reason>(detail);
  switch (code) {
    case link::NoticeCode::undo_refused:
      if (reason == input::Reason::busy) return "Undo waits until the stroke ends";
      break;
    case link::NoticeCode::redo_refused:
      if (reason == input::Reason::busy) return "Redo waits until the stroke ends";
      break;
    case link::NoticeCode::nothing_to_act_on:
      switch (reason) {
        case input::Reason::no_tracking:
          return "That handle is not tracked: bring it back in view";
        case input::Reason::same_point:
          return "Both hands on one spot: grab a little further away";
        case input::Reason::hand_busy:
          return "That hand is busy already";
        case input::Reason::object_busy:
          return "The other hand is moving the model";
        case input::Reason::hands_too_close:
          return "Hands too close together to set the size";
        case input::Reason::busy:
          return "Finish the stroke first";
        case input::Reason::not_available:
          return "That does nothing on this station";
        default:
          break;
      }
      break;
    default:
      break;
  }
  return notice_sentence(code);
}

std::string notice_name(link::NoticeCode code) {
  switch (code) {
    case link::NoticeCode::undo_refused:
      return "undo refused";
    case link::NoticeCode::redo_refused:
      return "redo refused";
    case link::NoticeCode::command_refused_spectator:
      return "command refused (spectator)";
    case link::NoticeCode::nothing_to_act_on:
      return "nothing to act on";
    case link::NoticeCode::sculpture_archived:
      return "sculpture archived";
    case link::NoticeCode::archive_failed:
      return "ARCHIVE FAILED";
    case link::NoticeCode::disk_full:
      return "DISK FULL";
    case link::NoticeCode::new_sculpture_undone:
      return "new sculpture undone";
    case link::NoticeCode::symmetry_changed:
      return "symmetry changed";
  }
  return "unknown notice";
}

std::string visitor_line(const SceneReplica& r) {
  if (!r.has_visitor()) return {};
  const link::VisitorState& v = r.visitor();
  char line[256];
  std::snprintf(line, sizeof line,
                "visitor: %s, visitor %u, sculpture %u, %u strokes, idle left %.0f s%s%s%s",
                phase_name(v.phase), v.visitor, v.sculpture, v.strokes,
                static_cast<double>(v.idle_left_s),
                (v.flags & link::kVisitorResetUndoable) != 0 ? ", undo reset open" : "",
                (v.flags & link::kVisitorArchiveFailed) != 0 ? ", ARCHIVE FAILED" : "",
                (v.flags & link::kVisitorDiskFull) != 0 ? ", DISK FULL" : "");
  std::string out = line;
  if (v.grace_left_s > 0.0F) {
    std::snprintf(line, sizeof line, " (%.0f s)", static_cast<double>(v.grace_left_s));
    out += line;
  }
  return out;
}

bool attract_mode(const SceneReplica& r) {
  return r.has_visitor() && r.visitor().phase == link::VisitorPhase::attract && !any_grab(r);
}

void ExhibitModel::local_notice(std::string text, double now_s) {
  shown_.push_back({std::move(text), now_s});
  while (shown_.size() > kNoticesShown) shown_.pop_front();
}

ExhibitText ExhibitModel::update(const SceneReplica& r, const HudInput& in, Audience audience) {
  ExhibitText out;
  // New notices from the station start their time now (each shown once).
  if (r.notices_received() != notices_seen_) {
    for (const ReceivedNotice& n : r.notices()) {
      if (n.number <= notices_seen_) continue;
      const std::string sentence = notice_sentence(n.notice.code, n.notice.detail);
      local_notice(audience == Audience::operator_hud ? notice_name(n.notice.code) + ": " + sentence
                                                      : sentence,
                   in.now_s);
    }
    notices_seen_ = r.notices_received();
  }
  while (!shown_.empty() && in.now_s - shown_.front().since_s >= kNoticeShowS) shown_.pop_front();
  for (const Shown& s : shown_) out.notices.push_back(s.text);
  out.attract = attract_mode(r);
  if (audience == Audience::visitor) visitor_words(r, in, out);
  // A notice saying what the prompt already says is not shown twice.
  std::erase(out.notices, out.prompt);
  return out;
}

}  // namespace twister::bridge
