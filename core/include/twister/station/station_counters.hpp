// StationCounters: what the station counts, grouped by the part that counts it:
// InputCounters by the tracker hands and the button drain (poses, button edges),
// EventCounters from the events themselves (EventCounters::count reads each event's
// kind and payload: one commit counts once however many hands it ends), and the
// checkpoints started over. Plain data.
#pragma once

#include <cstdint>

#include "twister/session/session_events.hpp"

namespace twister::station {

struct InputCounters {
  std::uint64_t poses = 0;          // converted poses used for a hand
  std::uint64_t pose_errors = 0;    // poses that failed conversion (skipped)
  std::uint64_t foreign_poses = 0;  // poses of receivers bound to no hand
  std::uint64_t button_edges = 0;   // from the ButtonSource and the stylus
  std::uint64_t button_errors = 0;  // ButtonSource io_error / out-of-range lines
};

struct EventCounters {
  // Committed warps (journal stroke records): one per release, freeze step or change
  // of the grabbing hands, however many hands took part.
  std::uint64_t strokes_committed = 0;
  std::uint64_t strokes_cancelled = 0;  // grabs dropped (per hand)
  // Commits (stroke segments, object moves) whose journal record could not be made
  // durable: not made, the model stays at the last saved record. One per commit,
  // however many hands it ended, like strokes_committed.
  std::uint64_t strokes_not_saved = 0;
  std::uint64_t undos = 0;
  std::uint64_t redos = 0;
  std::uint64_t refined_commits = 0;  // commits that refined the mesh
  std::uint64_t refine_stops = 0;     // of them, stopped at the mesh's capacity
  std::uint64_t refused = 0;
  // Failed journal appends (commits and undo/redo not saved) and checkpoint writes.
  std::uint64_t journal_errors = 0;
  std::uint64_t checkpoints_written = 0;
  std::uint64_t checkpoints_failed = 0;      // the sink failed (the previous one stays)
  std::uint64_t session_events_dropped = 0;  // a session step had more than it holds
  std::uint64_t events_dropped = 0;          // event queue full (the log is behind)

  // Counts one event (every event the station reports passes here once).
  void count(const session::SessionEvent& event);
};

struct StationCounters {
  InputCounters input{};
  EventCounters events{};
  std::uint64_t checkpoints_restarted = 0;  // the model changed while one was written
};

}  // namespace twister::station
