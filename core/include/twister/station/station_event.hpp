// StationEvent: what the station reports to the composition root's log (tracker
// up/down, strokes committed, not saved or cancelled, refusals, checkpoints, journal
// and button failures, and what the sculptor did besides strokes: radius, clutch,
// turn limit, undo/redo, method; adaptive refinement of a commit and where it
// stopped). Plain data; the station never formats text (log lines:
// hal/twister-station/station_log.hpp).
#pragma once

#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/ports/clock.hpp"

namespace twister::station {

enum class StationEventKind : std::uint8_t {
  journal_recovered,    // start(): `sequence` records in the journal (all of them, also
                        // those a checkpoint restored); `value` torn-tail bytes cut
  tracker_streaming,    // the Fastrak session reached streaming (value = start-ups so far)
  tracker_lost,         // streaming stopped (unplug, silence, garbage); re-init follows
  stroke_begin,         // hand grabbed
  stroke_committed,     // journal record `sequence` appended and synced
  stroke_cancelled,     // dropped; model unchanged. value = input::Reason: tracking_timeout
                        // (tracking lost too long), none (the station stopping, or a
                        // warp-plan error: status not ok)
  refused,              // a press was refused; value = input::Reason
  journal_error,        // a journal operation failed; status says how
  button_source_error,  // the button device failed; status says how
  stroke_not_saved,     // a commit (stroke segment or object move; `hand`) was NOT made:
                        // its record could not be made durable (status, e.g. io_error
                        // for a full disk); the model is back at the last saved record.
                        // value: input::Reason (released: the hand's grab ended)
  checkpoint_written,   // a checkpoint holding the first `sequence` records; value: bytes
  checkpoint_failed,    // writing a checkpoint failed (status); the previous one stays
  radius_set,           // the radius gesture ended; real = the radius (metres)
  hand_disengaged,      // freeze pressed: committed (sequence), the hand moves freely
  hand_engaged,         // freeze released: the hand warps again from where it is
  turn_limit_reached,   // the hand turned past the limit (real, radians): the warp holds
  turn_limit_left,      // back within the limit: the warp follows again
  undone,               // undo; sequence = its record
  redone,               // redo; sequence = its record
  method_changed,       // value = the math::WarpMethod of strokes from now on
  command_refused,      // value = session::SessionCommandKind, detail = input::Reason;
                        // status io_error: an undo/redo not saved (taken back)
  stroke_refined,       // commit `sequence` refined the mesh: value = vertices added
  refinement_stopped,   // its refinement stopped at a capacity: value = mesh::RefineStop
                        // (status resource_exhausted); the stroke is committed
                        // (the last kind: tests iterate up to it)
};

const char* station_event_kind_name(StationEventKind kind);

struct StationEvent {
  StationEventKind kind = StationEventKind::tracker_lost;
  std::uint8_t hand = 0;
  std::uint32_t sequence = 0;
  std::uint64_t value = 0;  // kind-specific (see above; committed/cancelled/refused: input::Reason)
  Status status{};
  ports::TimestampUs time_us = 0;
  double real = 0.0;        // kind-specific real (radius_set, turn_limit_reached)
  std::uint8_t detail = 0;  // command_refused: input::Reason
};

}  // namespace twister::station
