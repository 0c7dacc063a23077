// SessionEvents: what one SculptSession step (or part of it) reports to the station
// and, through it, the log and the display: strokes beginning, committing, not saved
// or being cancelled, the clutch, the turn limit, tracking, refusals, the radius,
// moves, undo/redo and method changes, in the order they happened. The display reads
// the lasting state from SculptSession::state(); events say when it changed. Fixed
// capacity; events beyond it are counted and dropped.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/status.hpp"
#include "twister/input/interaction_machine.hpp"

namespace twister::session {

enum class SessionEventKind : std::uint8_t {
  grab_begin,     // hand started a stroke
  committed,      // a stroke segment was applied to the mesh (sequence = its record);
                  // reason released: `hand`'s grab ends here; none: freeze or a
                  // hand joining, the stroke goes on. `repeat`: no new record (another
                  // hand of the same commit, or a grab ending with nothing left to
                  // commit: its last freeze step was the commit)
  cancelled,      // `hand`'s grab ended without commit: reason tracking_timeout
                  // (segment dropped, model as at its start) or a warp-plan error
                  // (status) when the stroke could not go on
  tracking_lost,  // hand lost tracking during a stroke or move; warp holds
  tracking_resumed,
  refused,         // a press was refused (reason; status for a plan error)
  radius_changed,  // the radius gesture changed the radius (value = radius, metres)
  move_begin,
  move_committed,
  move_cancelled,
  undone,              // sequence = the undo record
  redone,              // sequence = the redo record
  not_saved,           // a commit was NOT made: its journal record could not be made
                       // durable (status io_error) or the warp could not apply; the
                       // model is as after the last saved commit. Strokes: reason
                       // released = `hand`'s grab ends here, none = the hands go on in
                       // a new segment (a hand joined); a failed freeze press or release
                       // (a chain step) ends the stroke (released, for every hand of it;
                       // `repeat` for all but the first). Moves: the object is back.
  history_overflow,    // the commit was too large to be undoable
  radius_set,          // the radius gesture ended (value = the radius, metres)
  disengaged,          // freeze pressed: committed, `hand` moves freely (same weights)
  engaged,             // freeze released: `hand` warps again from its current pose
  turn_limit_reached,  // `hand` turned past the limit (value = limit, radians): holds
  turn_limit_left,     // `hand` turned back within the limit: follows again
  method_changed,      // value = the new math::WarpMethod (for strokes begun from now)
  command_refused,     // value = the SessionCommandKind; reason busy / nothing_to_*, or
                       // status io_error: an undo/redo whose record could not be saved
                       // (taken back: the model is unchanged)
  refined,             // the commit `sequence` refined the mesh (value = vertices added)
  refine_stopped,      // its refinement stopped at a capacity (value = mesh::RefineStop;
                       // status resource_exhausted): the commit stands, the mesh is
                       // conforming, edges over the threshold are left
};
const char* session_event_kind_name(SessionEventKind kind);

struct SessionEvent {
  SessionEventKind kind = SessionEventKind::committed;
  std::uint8_t hand = 0;
  input::Reason reason = input::Reason::none;
  Status status{};
  std::uint32_t sequence = 0;  // journal sequence of committed / undone / redone
  double value = 0.0;          // kind-specific number (see the kinds)
  bool repeat = false;         // committed / not_saved: reports a commit already counted
};

// A step's actions (at most 8, a few events each: a commit, the clutch, the turn
// limit) plus its commands (at most 8 from buttons and 8 submitted) fit.
inline constexpr std::size_t kMaxEventsPerStep = 32;

class SessionEvents {
 public:
  void push(const SessionEvent& event);  // beyond capacity: counted, dropped
  std::span<const SessionEvent> items() const { return {items_.data(), count_}; }
  std::size_t dropped() const { return dropped_; }

 private:
  std::array<SessionEvent, kMaxEventsPerStep> items_{};
  std::size_t count_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace twister::session
