// SessionEvents: what one SculptSession step (or part of it) reports to the station:
// strokes beginning, committing, not saved or being cancelled, tracking, refusals,
// moves, undo/redo, in the order they happened. Fixed capacity; events
// beyond it are counted and dropped.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/status.hpp"
#include "twister/input/interaction_machine.hpp"

namespace twister::input {

enum class SessionEventKind : std::uint8_t {
  grab_begin,     // hand started a stroke
  committed,      // a stroke segment was applied to the mesh (sequence = its record);
                  // reason released: `hand`'s grab ends here; none: freeze or a
                  // hand joining, the stroke goes on
  cancelled,      // `hand`'s grab ended without commit: reason tracking_timeout
                  // (segment dropped, model as at its start) or a warp-plan error
                  // (status) when the stroke could not go on
  tracking_lost,  // hand lost tracking during a stroke or move; warp holds
  tracking_resumed,
  refused,  // a press was refused (reason; status for a plan error)
  radius_changed,
  move_begin,
  move_committed,
  move_cancelled,
  undone,
  redone,
  not_saved,         // a commit was NOT made: its journal record could not be made
                     // durable (status io_error) or the warp could not apply; the model
                     // is as after the last saved commit. Strokes: reason released =
                     // `hand`'s grab ends here, none = the hands go on in a new segment
                     // (a hand joined); a failed freeze ends the stroke (released, for
                     // every hand of it). Moves: the object is back where it was.
  history_overflow,  // the commit was too large to be undoable
};
const char* session_event_kind_name(SessionEventKind kind);

struct SessionEvent {
  SessionEventKind kind = SessionEventKind::committed;
  std::uint8_t hand = 0;
  Reason reason = Reason::none;
  Status status{};
  std::uint32_t sequence = 0;  // journal sequence of committed / undone / redone
};

inline constexpr std::size_t kMaxEventsPerStep = 16;

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

}  // namespace twister::input
