#include "twister/station/station_counters.hpp"

namespace twister::station {

void EventCounters::count(const session::SessionEvent& e) {
  using K = session::SessionEventKind;
  switch (e.kind) {
    case K::committed:
      // One commit, however many hands it ends (repeat: already counted).
      if (!e.stroke_end().repeat && e.status.ok()) ++strokes_committed;
      return;
    case K::cancelled:
      ++strokes_cancelled;
      return;
    case K::refused:
      ++refused;
      return;
    case K::not_saved:
      // One commit not made, however many hands it ends (repeat: already counted).
      if (!e.stroke_end().repeat) {
        ++strokes_not_saved;
        ++journal_errors;
      }
      return;
    case K::undone:
      ++undos;
      return;
    case K::redone:
      ++redos;
      return;
    case K::command_refused:
      // io_error: an undo/redo whose record could not be saved (taken back).
      if (e.status.code() == StatusCode::io_error) ++journal_errors;
      return;
    case K::refined:
      ++refined_commits;
      return;
    case K::refine_stopped:
      ++refine_stops;
      return;
    case K::checkpoint_written:
      ++checkpoints_written;
      return;
    case K::checkpoint_failed:
      ++checkpoints_failed;
      ++journal_errors;
      return;
    default:
      return;  // the rest is in the session's state or the tracker's counters
  }
}

}  // namespace twister::station
