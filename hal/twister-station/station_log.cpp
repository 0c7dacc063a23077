#include "station_log.hpp"

#include <cerrno>
#include <cstring>
#include <numbers>

#include "twister/input/interaction_machine.hpp"
#include "twister/session/session_command.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/mesh/mesh_refiner.hpp"

namespace twister::station_app {
namespace {

using ports::LogLevel;
using station::StationEvent;
using station::StationEventKind;

const char* reason_text(std::uint64_t value) {
  return input::reason_name(static_cast<input::Reason>(value));
}

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

// Station::stop() cancels an open stroke with reason none and no error.
bool station_stopping(const StationEvent& e) {
  return e.status.ok() && static_cast<input::Reason>(e.value) == input::Reason::none;
}

const char* method_text(std::uint64_t value) {
  return value < 3 ? math::warp_method_name(static_cast<math::WarpMethod>(value)).data() : "?";
}

// Which capacity stopped a refinement, in station.toml's words.
const char* capacity_text(std::uint64_t value) {
  switch (static_cast<mesh::RefineStop>(value)) {
    case mesh::RefineStop::vertex_capacity:
      return "vertex capacity";
    case mesh::RefineStop::triangle_capacity:
      return "triangle capacity";
    case mesh::RefineStop::done:
      break;
  }
  return "capacity";
}

const char* command_text(std::uint64_t value) {
  return value < session::kSessionCommandKindCount
             ? session::session_command_name(static_cast<session::SessionCommandKind>(value))
             : "?";
}

// The journal: recovery, checkpoints, commits that were not saved, failures.
bool log_journal(const StationEvent& e, ports::LogSink& log, int storage_errno) {
  const LogLevel level = station_event_level(e);
  switch (e.kind) {
    case StationEventKind::journal_recovered:
      if (e.value == 0) {
        log.write(level, "journal", "%u good records", {e.sequence});
      } else {
        log.write(level, "journal", "%u good records, cut a torn tail of %u bytes",
                  {e.sequence, e.value});
      }
      return true;
    case StationEventKind::checkpoint_written:
      log.write(level, "journal", "checkpoint of %u records written (%u bytes)",
                {e.sequence, e.value});
      return true;
    case StationEventKind::checkpoint_failed:
      log.write(level, "journal", "checkpoint not written (%s); the previous one stays",
                {e.status.name()});
      return true;
    case StationEventKind::journal_error:
      log.write(level, "journal", "%s (%s)", {e.status.name(), storage_error_text(storage_errno)});
      return true;
    case StationEventKind::stroke_not_saved:
      log.write(level, "stroke",
                "hand %u: stroke not saved: %s (%s); the model is back at the last saved stroke",
                {static_cast<unsigned>(e.hand),
                 e.status.code() == StatusCode::io_error ? storage_error_text(storage_errno)
                                                         : "the warp could not be applied",
                 e.status.name()});
      return true;
    default:
      return false;
  }
}

// Trouble and the station's own life (tracker, buttons).
bool log_station_side(const StationEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  switch (e.kind) {
    case StationEventKind::tracker_streaming:
      log.write(level, "tracker", "streaming (start-up #%u)", {e.value});
      return true;
    case StationEventKind::tracker_lost:
      log.write(level, "tracker",
                "lost (unplugged, silent or garbled); waiting and re-initialising");
      return true;
    case StationEventKind::button_source_error:
      log.write(level, "buttons", "device failed (%s); reopening", {e.status.name()});
      return true;
    case StationEventKind::refinement_stopped:
      log.write(level, "refine",
                "journal record %u: refinement stopped, the mesh's %s is used up "
                "(station.spare_vertices); the stroke is committed and the mesh conforming, "
                "some edges stay coarser than sculpt.refine_threshold_m",
                {e.sequence, capacity_text(e.value)});
      return true;
    default:
      return false;
  }
}

void log_strokes(const StationEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  const unsigned hand = e.hand;
  switch (e.kind) {
    case StationEventKind::stroke_begin:
      log.write(level, "stroke", "hand %u grabbed", {hand});
      return;
    case StationEventKind::stroke_committed:
      log.write(level, "stroke", "hand %u committed as journal record %u", {hand, e.sequence});
      return;
    case StationEventKind::stroke_cancelled:
      if (station_stopping(e)) {
        log.write(level, "stroke", "hand %u cancelled (station stopping); model unchanged", {hand});
      } else if (e.status.ok()) {
        log.write(level, "stroke", "hand %u cancelled (tracking lost too long); model unchanged",
                  {hand});
      } else {
        log.write(level, "stroke", "hand %u cancelled (%s); model as at the last commit",
                  {hand, e.status.name()});
      }
      return;
    case StationEventKind::refused:
      log.write(level, "stroke", "press refused: hand %u (%s)", {hand, reason_text(e.value)});
      return;
    case StationEventKind::hand_disengaged:
      log.write(level, "stroke",
                "hand %u on the clutch (freeze held): committed as journal record %u; the hand "
                "moves freely",
                {hand, e.sequence});
      return;
    case StationEventKind::hand_engaged:
      log.write(level, "stroke", "hand %u off the clutch: warping again from where it is", {hand});
      return;
    case StationEventKind::turn_limit_reached:
      log.write(level, "stroke",
                "hand %u turned past the %.0f-degree limit; the warp holds until the hand "
                "turns back",
                {hand, degrees(e.real)});
      return;
    case StationEventKind::turn_limit_left:
      log.write(level, "stroke", "hand %u back within the turn limit; the warp follows again",
                {hand});
      return;
    case StationEventKind::stroke_refined:
      log.write(level, "refine", "journal record %u refined: %u vertices added",
                {e.sequence, e.value});
      return;
    default:
      return;
  }
}

void log_session(const StationEvent& e, ports::LogSink& log, int storage_errno) {
  const LogLevel level = station_event_level(e);
  switch (e.kind) {
    case StationEventKind::radius_set:
      log.write(level, "sculpt", "radius %.3f m", {e.real});
      return;
    case StationEventKind::method_changed:
      log.write(level, "sculpt", "warp method %s for the next strokes", {method_text(e.value)});
      return;
    case StationEventKind::undone:
      log.write(level, "history", "undo (journal record %u)", {e.sequence});
      return;
    case StationEventKind::redone:
      log.write(level, "history", "redo (journal record %u)", {e.sequence});
      return;
    case StationEventKind::command_refused:
      if (e.status.code() == StatusCode::io_error) {
        log.write(level, "history", "%s not saved: %s (%s); the model is unchanged",
                  {command_text(e.value), storage_error_text(storage_errno), e.status.name()});
      } else {
        log.write(level, "history", "%s refused (%s)",
                  {command_text(e.value), reason_text(e.detail)});
      }
      return;
    default:
      return;
  }
}

}  // namespace

const char* storage_error_text(int storage_errno) {
  switch (storage_errno) {
    case 0:
      return "i/o failure";
    case ENOSPC:
      return "disk full";
    case EFBIG:
      return "file size limit reached";
    case EDQUOT:
      return "disk quota exceeded";
    default:
      return std::strerror(storage_errno);
  }
}

LogLevel station_event_level(const StationEvent& e) {
  switch (e.kind) {
    case StationEventKind::journal_error:
    case StationEventKind::stroke_not_saved:  // the sculptor's work was lost
      return LogLevel::error;
    case StationEventKind::button_source_error:  // reopened by the loop: trouble, not failure
    case StationEventKind::tracker_lost:
    case StationEventKind::checkpoint_failed:  // the previous one stays; start-up replays more
    case StationEventKind::refinement_stopped:
      return LogLevel::warning;
    case StationEventKind::stroke_cancelled:  // the stop policy is no trouble
      return station_stopping(e) ? LogLevel::notice : LogLevel::warning;
    case StationEventKind::command_refused:  // io_error: an undo/redo not saved
      return e.status.code() == StatusCode::io_error ? LogLevel::error : LogLevel::notice;
    case StationEventKind::journal_recovered:
    case StationEventKind::tracker_streaming:
    case StationEventKind::refused:
    case StationEventKind::radius_set:
    case StationEventKind::turn_limit_reached:
    case StationEventKind::undone:
    case StationEventKind::redone:
    case StationEventKind::method_changed:
      return LogLevel::notice;
    case StationEventKind::stroke_begin:
    case StationEventKind::stroke_committed:
    case StationEventKind::checkpoint_written:
    case StationEventKind::hand_disengaged:
    case StationEventKind::hand_engaged:
    case StationEventKind::turn_limit_left:
    case StationEventKind::stroke_refined:
      return LogLevel::info;
  }
  return LogLevel::notice;
}

void log_station_event(const StationEvent& e, ports::LogSink& log, int storage_errno) {
  if (log_journal(e, log, storage_errno) || log_station_side(e, log)) return;
  log_strokes(e, log);
  log_session(e, log, storage_errno);
}

}  // namespace twister::station_app
