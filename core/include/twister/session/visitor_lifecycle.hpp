// VisitorLifecycle: the exhibit's visitor cycle (issue 25), attract -> sculpting ->
// finished -> attract, as a pure state machine of time and a few inputs. The station
// (StationExhibit) feeds it once per poll and does what its actions say (archive the
// sculpture, reset the model); it owns no model, file or clock.
//
//   attract ── activity (a grab or an object move) ──► sculpting
//   sculpting ── idle for idle_us (no grab, no move, no hand moved more than
//                motion_threshold_m) ──────────────────► finished (end idle)
//   sculpting ── the new-sculpture chord held chord_hold_us, or request_new() ──► finished
//   finished ── a grab, the chord again, request_undo() ──► sculpting (undone)
//   finished ── grace_us over ──► action archive; archived(true) ──► attract
//                                 archived(false) ──► stays finished, archive again
//                                 after retry_us (the model is never reset without
//                                 a durable archive)
//
// The finished phase is the grace: the visitor's model stays as it is (nothing is reset
// yet), so "undo the reset" is going back to sculpting; the reset happens once the
// archive is durable. Allocation-free, no exceptions; plain data in and out.
#pragma once

#include <array>
#include <cstdint>

#include "twister/ports/clock.hpp"

namespace twister::session {

enum class VisitorPhase : std::uint8_t { attract = 0, sculpting = 1, finished = 2 };
const char* visitor_phase_name(VisitorPhase phase);

// Why a sculpture ended (its archive record says so).
enum class SculptureEnd : std::uint8_t { none = 0, idle = 1, chord = 2, command = 3 };
const char* sculpture_end_name(SculptureEnd end);

// What the station reports about the lifecycle (SessionEventKind::visitor).
enum class VisitorNote : std::uint8_t {
  began = 0,           // a visitor's first grab: sculpting
  ended = 1,           // the sculpture ended (idle, chord, command): the grace runs
  undone = 2,          // the end was undone in the grace: sculpting again
  archived = 3,        // archived, the journal rotated, the model is the base again
  archive_failed = 4,  // the archive could not be written (status): tried again later,
                       // the model and the journal stay as they are
  disk_full = 5,       // ... because the archive's disk is full
  refused = 6,         // new / undo command (or chord) with nothing to act on
  rotate_failed = 7,   // archived, but the new journal could not be begun (status):
                       // strokes are not saved until it can (tried again)
};
const char* visitor_note_name(VisitorNote note);

struct VisitorConfig {
  bool enabled = false;  // exhibit mode off: the lifecycle never acts
  ports::TimestampUs idle_us = 90'000'000;
  ports::TimestampUs grace_us = 6'000'000;       // 0: archive at once
  ports::TimestampUs chord_hold_us = 1'500'000;  // how long the chord is held
  ports::TimestampUs retry_us = 5'000'000;       // a failed archive is tried again after
  double motion_threshold_m = 0.02;              // a hand moving less is idle
};

struct VisitorInputs {
  bool active = false;      // a stroke or an object move is open
  bool chord_held = false;  // every line of the new-sculpture chord is held
  std::array<bool, 2> tracked{};
  std::array<std::array<double, 3>, 2> hand_m{};  // hand positions (world, metres)
};

enum class VisitorAction : std::uint8_t {
  none,
  began,    // attract -> sculpting (a new visitor's first grab)
  ended,    // sculpting -> finished (end() says why)
  undone,   // finished -> sculpting
  archive,  // the grace is over: archive the sculpture now, then call archived()
  refused,  // request_new / request_undo with nothing to act on
};

class VisitorLifecycle {
 public:
  explicit VisitorLifecycle(const VisitorConfig& config) : config_(config) {}

  // Start-up: sculpting when the journal holds a sculpture, attract when it is empty.
  void start(bool has_sculpture, ports::TimestampUs now_us);

  VisitorAction step(const VisitorInputs& in, ports::TimestampUs now_us);
  // The display's new_sculpture command: sculpting -> finished (refused otherwise).
  VisitorAction request_new(ports::TimestampUs now_us);
  // The display's undo_new_sculpture: finished -> sculpting (refused otherwise).
  VisitorAction request_undo(ports::TimestampUs now_us);
  // What came of the archive asked for by `archive`.
  void archived(bool ok, ports::TimestampUs now_us);

  VisitorPhase phase() const { return phase_; }
  SculptureEnd end() const { return end_; }
  bool enabled() const { return config_.enabled; }
  // Seconds of idle left before the sculpture ends (sculpting; else 0).
  ports::TimestampUs idle_left_us(ports::TimestampUs now_us) const;
  // Grace left before the archive (finished; 0 while an archive is due or retried).
  ports::TimestampUs grace_left_us(ports::TimestampUs now_us) const;
  // In the grace: the end can still be undone.
  bool undoable() const { return phase_ == VisitorPhase::finished; }
  bool archive_pending() const { return phase_ == VisitorPhase::finished && archive_failed_; }

 private:
  void finish(SculptureEnd why, ports::TimestampUs now_us);
  bool moved(const VisitorInputs& in) const;
  void remember(const VisitorInputs& in);

  VisitorConfig config_;
  VisitorPhase phase_ = VisitorPhase::attract;
  SculptureEnd end_ = SculptureEnd::none;
  ports::TimestampUs activity_us_ = 0;  // last activity (sculpting)
  ports::TimestampUs phase_us_ = 0;     // when finished began, or the failed archive
  ports::TimestampUs chord_since_us_ = -1;
  bool chord_latched_ = false;  // the chord acted: it must be released before it acts again
  bool archive_failed_ = false;
  std::array<bool, 2> ref_valid_{};
  std::array<std::array<double, 3>, 2> ref_m_{};
};

}  // namespace twister::session
