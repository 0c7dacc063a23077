#include "twister/session/visitor_lifecycle.hpp"

#include <algorithm>

namespace twister::session {

const char* visitor_phase_name(VisitorPhase phase) {
  switch (phase) {
    case VisitorPhase::attract:
      return "attract";
    case VisitorPhase::sculpting:
      return "sculpting";
    case VisitorPhase::finished:
      return "finished";
  }
  return "unknown";
}

const char* sculpture_end_name(SculptureEnd end) {
  switch (end) {
    case SculptureEnd::none:
      return "none";
    case SculptureEnd::idle:
      return "idle";
    case SculptureEnd::chord:
      return "chord";
    case SculptureEnd::command:
      return "command";
  }
  return "unknown";
}

const char* visitor_note_name(VisitorNote note) {
  switch (note) {
    case VisitorNote::began:
      return "began";
    case VisitorNote::ended:
      return "ended";
    case VisitorNote::undone:
      return "undone";
    case VisitorNote::archived:
      return "archived";
    case VisitorNote::archive_failed:
      return "archive_failed";
    case VisitorNote::disk_full:
      return "disk_full";
    case VisitorNote::refused:
      return "refused";
    case VisitorNote::rotate_failed:
      return "rotate_failed";
  }
  return "unknown";
}

void VisitorLifecycle::start(bool has_sculpture, ports::TimestampUs now_us) {
  phase_ = has_sculpture ? VisitorPhase::sculpting : VisitorPhase::attract;
  end_ = SculptureEnd::none;
  activity_us_ = now_us;
  phase_us_ = now_us;
  chord_since_us_ = -1;
  chord_latched_ = false;
  archive_failed_ = false;
  ref_valid_ = {};
}

bool VisitorLifecycle::moved(const VisitorInputs& in) const {
  const double limit2 = config_.motion_threshold_m * config_.motion_threshold_m;
  for (std::size_t h = 0; h < in.tracked.size(); ++h) {
    if (!in.tracked[h]) continue;
    if (!ref_valid_[h]) return true;  // a hand coming into view is motion
    double d2 = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = in.hand_m[h][k] - ref_m_[h][k];
      d2 += d * d;
    }
    if (d2 > limit2) return true;
  }
  return false;
}

void VisitorLifecycle::remember(const VisitorInputs& in) {
  ref_valid_ = in.tracked;
  ref_m_ = in.hand_m;
}

void VisitorLifecycle::finish(SculptureEnd why, ports::TimestampUs now_us) {
  phase_ = VisitorPhase::finished;
  end_ = why;
  phase_us_ = now_us;
  archive_failed_ = false;
}

VisitorAction VisitorLifecycle::step(const VisitorInputs& in, ports::TimestampUs now_us) {
  if (!config_.enabled) return VisitorAction::none;
  if (!in.chord_held) {
    chord_since_us_ = -1;
    chord_latched_ = false;
  } else if (chord_since_us_ < 0) {
    chord_since_us_ = now_us;
  }
  const bool chord =
      in.chord_held && !chord_latched_ && now_us - chord_since_us_ >= config_.chord_hold_us;
  if (chord) chord_latched_ = true;
  // Motion counts from where the hands were when sculpting (re)started.
  if (phase_ != VisitorPhase::sculpting) remember(in);
  switch (phase_) {
    case VisitorPhase::attract:
      if (in.active) {
        phase_ = VisitorPhase::sculpting;
        end_ = SculptureEnd::none;
        activity_us_ = now_us;
        return VisitorAction::began;
      }
      return chord ? VisitorAction::refused : VisitorAction::none;
    case VisitorPhase::sculpting:
      if (in.active || moved(in)) {
        activity_us_ = now_us;
        remember(in);
      }
      if (chord) {
        finish(SculptureEnd::chord, now_us);
        return VisitorAction::ended;
      }
      if (!in.active && now_us - activity_us_ >= config_.idle_us) {
        finish(SculptureEnd::idle, now_us);
        return VisitorAction::ended;
      }
      return VisitorAction::none;
    case VisitorPhase::finished:
      if (in.active || chord) return request_undo(now_us);
      if (archive_failed_ ? now_us - phase_us_ >= config_.retry_us
                          : now_us - phase_us_ >= config_.grace_us) {
        return VisitorAction::archive;
      }
      return VisitorAction::none;
  }
  return VisitorAction::none;
}

VisitorAction VisitorLifecycle::request_new(ports::TimestampUs now_us) {
  if (!config_.enabled || phase_ != VisitorPhase::sculpting) return VisitorAction::refused;
  finish(SculptureEnd::command, now_us);
  return VisitorAction::ended;
}

VisitorAction VisitorLifecycle::request_undo(ports::TimestampUs now_us) {
  if (!config_.enabled || phase_ != VisitorPhase::finished) return VisitorAction::refused;
  phase_ = VisitorPhase::sculpting;
  end_ = SculptureEnd::none;
  activity_us_ = now_us;
  archive_failed_ = false;
  return VisitorAction::undone;
}

void VisitorLifecycle::archived(bool ok, ports::TimestampUs now_us) {
  if (phase_ != VisitorPhase::finished) return;
  if (ok) {
    phase_ = VisitorPhase::attract;
    end_ = SculptureEnd::none;
    archive_failed_ = false;
    ref_valid_ = {};
    return;
  }
  archive_failed_ = true;
  phase_us_ = now_us;
}

ports::TimestampUs VisitorLifecycle::idle_left_us(ports::TimestampUs now_us) const {
  if (phase_ != VisitorPhase::sculpting) return 0;
  return std::max<ports::TimestampUs>(0, config_.idle_us - (now_us - activity_us_));
}

ports::TimestampUs VisitorLifecycle::grace_left_us(ports::TimestampUs now_us) const {
  if (phase_ != VisitorPhase::finished || archive_failed_) return 0;
  return std::max<ports::TimestampUs>(0, config_.grace_us - (now_us - phase_us_));
}

}  // namespace twister::session
