// SessionCommand: a request to a SculptSession that is not a hand gesture: undo, redo
// and the warp method. Buttons give them (ButtonRole undo / redo / method_cycle) and
// so may a display (keyboard commands over the link, a later issue) through
// SculptSession::submit(); both run through the same code at the end of a step and
// report through the step's events (undone, redone, method_changed, command_refused).
#pragma once

#include <cstddef>
#include <cstdint>

#include "twister/math/warp_method.hpp"

namespace twister::session {

enum class SessionCommandKind : std::uint8_t {
  undo,                // undo the newest commit (journaled); refused while a stroke/move is open
  redo,                // redo the newest undone commit (journaled); likewise
  next_method,         // twister -> rottran -> scodef -> twister, for strokes begun from now on
  set_method,          // `method`, for strokes begun from now on
  cycle_symmetry,      // the next group in the configured cycle, for strokes begun from now on
  new_sculpture,       // exhibit: end this visitor's sculpture (archive, reset to the base)
  undo_new_sculpture,  // exhibit: within the grace time, bring the ended sculpture back
};
inline constexpr std::uint8_t kSessionCommandKindCount = 7;
// "undo", "redo", "next_method", "set_method", "cycle_symmetry", "new_sculpture",
// "undo_new_sculpture".
const char* session_command_name(SessionCommandKind kind);

struct SessionCommand {
  SessionCommandKind kind = SessionCommandKind::undo;
  std::uint8_t hand = 0;  // the hand whose button gave it (< kHandCount; a display: 0)
  math::WarpMethod method = math::WarpMethod::twister;  // set_method only
};

// Commands a session queues between two steps (submit()).
inline constexpr std::size_t kMaxQueuedCommands = 8;

}  // namespace twister::session
