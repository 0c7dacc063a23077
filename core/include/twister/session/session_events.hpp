// SessionEvent: the station's one event vocabulary, from the sculpting session out to
// the log, the counters and the display. The session reports what the sculptor did
// (strokes beginning, committing, not saved or cancelled, the clutch, the turn limit,
// tracking, refusals, the radius, moves, undo/redo, method changes, refinement); the
// station adds its own (tracker up and down, the journal recovered, checkpoints, the
// button device failing) to the same stream and stamps the time. Each kind carries a
// typed payload (one of the small structs in `payload`, or none), read through the
// accessors, which check the kind. Nothing translates one event into another on the way
// out: the station queues them as they come, the log and the counters read fields.
// The display reads the lasting state from SculptSession::state(); events say when it
// changed. A step's events have a fixed capacity; events beyond it are counted and
// dropped. Plain data, no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "twister/base/assert.hpp"
#include "twister/base/inline_vector.hpp"
#include "twister/base/status.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/session_command.hpp"
#include "twister/session/visitor_lifecycle.hpp"

namespace twister::session {

// The payload each kind carries is named after the kind (`-> Type`); "none": only
// the hand and the status.
enum class SessionEventKind : std::uint8_t {
  // The session (what the sculptor did).
  grab_begin,          // `hand` started a stroke. none
  committed,           // a stroke segment was applied to the mesh -> StrokeEnd (sequence = its
                       // record). reason released: `hand`'s grab ends here; none: freeze or a hand
                       // joining, the stroke goes on. `repeat`: no new record (another hand of
                       // the same commit, or a grab ending with nothing left to commit: its last
                       // freeze step was the commit)
  cancelled,           // `hand`'s grab ended without commit -> StrokeEnd: reason tracking_timeout
                       // (segment dropped, model as at its start), stopped (the station stops),
                       // or none with a warp-plan error (status) when the stroke could not go on
  tracking_lost,       // `hand` lost tracking during a stroke or move; the warp holds. none
  tracking_resumed,    // none
  refused,             // a press was refused -> Reasoned (status: a plan error)
  radius_changed,      // the radius gesture changed the radius -> Radius
  move_begin,          // `hand` started moving the object. none
  move_committed,      // -> RecordRef (the object_move record)
  move_cancelled,      // the object is back -> Reasoned (tracking_timeout, stopped)
  undone,              // -> RecordRef (the undo record)
  redone,              // -> RecordRef (the redo record)
  not_saved,           // a commit was NOT made -> StrokeEnd: its journal record could not be
                       // made durable (status io_error) or the warp could not apply; the
                       // model is as after the last saved commit. Strokes: reason released =
                       // `hand`'s grab ends here, none = the hands go on in a new segment (a
                       // hand joined); a failed freeze press or release (a chain step) ends
                       // the stroke (released, for every hand of it; `repeat` for all but the
                       // first). Moves: the object is back.
  history_overflow,    // the commit was too large to be undoable -> RecordRef
  radius_set,          // the radius gesture ended -> Radius
  disengaged,          // freeze pressed: committed, `hand` moves freely (same weights)
                       // -> RecordRef (the freeze step's record)
  engaged,             // freeze released: `hand` warps again from its current pose. none
  turn_limit_reached,  // `hand` turned past the limit: the warp holds -> TurnLimit
  turn_limit_left,     // `hand` turned back within the limit: follows again -> TurnLimit
  method_changed,      // -> Method (for strokes begun from now)
  symmetry_changed,    // -> Symmetry: the group of strokes begun from now (cycle_symmetry)
  command_refused,     // -> CommandRefusal: reason busy / nothing_to_*, or status
                       // io_error: an undo/redo whose record could not be saved (taken
                       // back: the model is unchanged)
  refined,             // a commit refined the mesh -> Refinement
  refine_stopped,      // its refinement stopped at a capacity -> RefinementStop (status
                       // resource_exhausted): the commit stands, the mesh is conforming,
                       // edges over the threshold are left
  // The station around the session.
  journal_recovered,   // start() -> JournalRecovered
  tracker_streaming,   // the Fastrak session reached streaming -> TrackerStreaming
  tracker_lost,        // streaming stopped (unplug, silence, garbage); re-init follows. none
  buttons_lost,        // the button device is missing (status unavailable: not there at
                       // start-up) or vanished (io_error); the station runs without it, ends
                       // the strokes of its buttons as on lost tracking, and opens it again
                       // when it appears. none
  buttons_found,       // the button device is back (opened again). none
  checkpoint_written,  // -> CheckpointWritten
  checkpoint_failed,   // writing a checkpoint failed (status); the previous one stays. none
  visitor,             // exhibit mode: the visitor lifecycle moved or the archive acted
                       // -> Visitor (status: why an archive or a rotation failed)
};
inline constexpr std::size_t kSessionEventKindCount =
    static_cast<std::size_t>(SessionEventKind::visitor) + 1;
const char* session_event_kind_name(SessionEventKind kind);

namespace payload {
// committed, not_saved, cancelled.
struct StrokeEnd {
  input::Reason reason = input::Reason::none;
  std::uint32_t sequence = 0;  // committed / not_saved: the record (made or not)
  bool repeat = false;         // reports a commit already counted (another hand of it)
};
// refused, move_cancelled.
struct Reasoned {
  input::Reason reason = input::Reason::none;
};
// radius_changed, radius_set.
struct Radius {
  double radius_m = 0.0;
};
// undone, redone, move_committed, disengaged, history_overflow: the journal record.
struct RecordRef {
  std::uint32_t sequence = 0;
};
// turn_limit_reached, turn_limit_left.
struct TurnLimit {
  double limit_rad = 0.0;
};
// method_changed.
struct Method {
  math::WarpMethod method = math::WarpMethod::twister;
};
// symmetry_changed.
struct Symmetry {
  math::SymmetrySpec spec{};
};
// command_refused.
struct CommandRefusal {
  SessionCommandKind command = SessionCommandKind::undo;
  input::Reason reason = input::Reason::none;
};
// refined.
struct Refinement {
  std::uint32_t sequence = 0;  // the commit's record
  std::uint32_t vertices_added = 0;
};
// refine_stopped.
struct RefinementStop {
  std::uint32_t sequence = 0;
  mesh::RefineStop stop = mesh::RefineStop::vertex_capacity;  // which capacity
};
// journal_recovered.
struct JournalRecovered {
  std::uint32_t records = 0;          // in the journal (also those a checkpoint restored)
  std::uint64_t torn_tail_bytes = 0;  // cut at start-up (0: none)
};
// checkpoint_written.
struct CheckpointWritten {
  std::uint32_t records = 0;  // the first `records` records of the journal
  std::uint64_t bytes = 0;
};
// tracker_streaming.
struct Visitor {
  VisitorNote note = VisitorNote::began;
  SculptureEnd end = SculptureEnd::none;  // ended: why
  std::uint32_t visitor = 0;              // today's number of the visitor it concerns
  std::uint32_t sculpture = 0;            // the sculpture's journal identity
  std::uint32_t records = 0;              // its journal records
};
struct TrackerStreaming {
  std::uint64_t start_ups = 0;  // streams started so far, this one included
};
}  // namespace payload

using EventPayload =
    std::variant<std::monostate, payload::StrokeEnd, payload::Reasoned, payload::Radius,
                 payload::RecordRef, payload::TurnLimit, payload::Method, payload::CommandRefusal,
                 payload::Refinement, payload::RefinementStop, payload::JournalRecovered,
                 payload::CheckpointWritten, payload::TrackerStreaming, payload::Symmetry,
                 payload::Visitor>;

// The EventPayload alternative (index) a kind carries.
std::size_t payload_index(SessionEventKind kind);

struct SessionEvent {
  SessionEventKind kind = SessionEventKind::grab_begin;
  std::uint8_t hand = 0;           // the hand it concerns (0 for the station's own)
  Status status{};                 // ok, or what failed
  ports::TimestampUs time_us = 0;  // stamped by the station when it queues the event
  EventPayload payload{};

  // The payload; each checks (TWISTER_ASSERT) that the kind carries it.
  const payload::StrokeEnd& stroke_end() const { return get<payload::StrokeEnd>(); }
  const payload::Reasoned& reasoned() const { return get<payload::Reasoned>(); }
  const payload::Radius& radius() const { return get<payload::Radius>(); }
  const payload::RecordRef& record() const { return get<payload::RecordRef>(); }
  const payload::TurnLimit& turn_limit() const { return get<payload::TurnLimit>(); }
  const payload::Method& method() const { return get<payload::Method>(); }
  const payload::CommandRefusal& command_refusal() const { return get<payload::CommandRefusal>(); }
  const payload::Symmetry& symmetry() const { return get<payload::Symmetry>(); }
  const payload::Refinement& refinement() const { return get<payload::Refinement>(); }
  const payload::RefinementStop& refinement_stop() const { return get<payload::RefinementStop>(); }
  const payload::Visitor& visitor() const { return get<payload::Visitor>(); }
  const payload::JournalRecovered& journal_recovered() const {
    return get<payload::JournalRecovered>();
  }
  const payload::CheckpointWritten& checkpoint_written() const {
    return get<payload::CheckpointWritten>();
  }
  const payload::TrackerStreaming& tracker_streaming() const {
    return get<payload::TrackerStreaming>();
  }

 private:
  template <class P>
  const P& get() const;
};

template <class P>
const P& SessionEvent::get() const {
  const P* p = std::get_if<P>(&payload);
  TWISTER_ASSERT(p != nullptr);
  return *p;
}

// The only way events are built: checks (TWISTER_ASSERT) that the payload is the
// kind's.
SessionEvent make_event(SessionEventKind kind, std::uint8_t hand, EventPayload payload = {},
                        Status status = ok_status());

// A step's actions (at most 8, a few events each: a commit, the clutch, the turn
// limit) plus its commands (at most 8 from buttons and 8 submitted) fit.
inline constexpr std::size_t kMaxEventsPerStep = 32;

class SessionEvents {
 public:
  void push(const SessionEvent& event);  // beyond capacity: counted, dropped
  std::span<const SessionEvent> items() const { return items_.span(); }
  std::size_t dropped() const { return dropped_; }

 private:
  InlineVector<SessionEvent, kMaxEventsPerStep> items_;
  std::size_t dropped_ = 0;
};

}  // namespace twister::session
