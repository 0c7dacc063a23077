#include "station_log.hpp"

#include <cerrno>
#include <cstring>
#include <numbers>

#include "twister/input/interaction_machine.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/session/session_command.hpp"
#include "twister/session/symmetry_cycle.hpp"

namespace twister::station_app {
namespace {

using ports::LogLevel;
using session::SessionEvent;
using K = session::SessionEventKind;

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

// Which capacity stopped a refinement, in station.toml's words.
const char* capacity_text(mesh::RefineStop stop) {
  switch (stop) {
    case mesh::RefineStop::vertex_capacity:
      return "vertex capacity";
    case mesh::RefineStop::triangle_capacity:
      return "triangle capacity";
    case mesh::RefineStop::done:
      break;
  }
  return "capacity";
}

// The journal: recovery, checkpoints, commits and history steps that were not saved.
bool log_journal(const SessionEvent& e, ports::LogSink& log, int storage_errno) {
  const LogLevel level = station_event_level(e);
  const char* c = station_event_component(e);
  switch (e.kind) {
    case K::journal_recovered: {
      const auto& r = e.journal_recovered();
      if (r.torn_tail_bytes == 0) {
        log.write(level, c, "%u good records", {r.records});
      } else {
        log.write(level, c, "%u good records, cut a torn tail of %u bytes",
                  {r.records, r.torn_tail_bytes});
      }
      return true;
    }
    case K::checkpoint_written:
      log.write(level, c, "checkpoint of %u records written (%u bytes)",
                {e.checkpoint_written().records, e.checkpoint_written().bytes});
      return true;
    case K::checkpoint_failed:
      log.write(level, c, "checkpoint not written (%s); the previous one stays", {e.status.name()});
      return true;
    case K::not_saved:
      log.write(level, c,
                "hand %u: stroke not saved: %s (%s); the model is back at the last saved stroke",
                {static_cast<unsigned>(e.hand),
                 e.status.code() == StatusCode::io_error ? storage_error_text(storage_errno)
                                                         : "the warp could not be applied",
                 e.status.name()});
      return true;
    case K::history_overflow:
      log.write(level, c,
                "journal record %u is committed but too large to undo (the undo memory is full)",
                {e.record().sequence});
      return true;
    default:
      return false;
  }
}

// The station's own devices and the refinement's capacity.
bool log_station_side(const SessionEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  const char* c = station_event_component(e);
  switch (e.kind) {
    case K::tracker_streaming:
      log.write(level, c, "streaming (start-up #%u)", {e.tracker_streaming().start_ups});
      return true;
    case K::tracker_lost:
      log.write(level, c, "lost (unplugged, silent or garbled); waiting and re-initialising");
      return true;
    case K::buttons_lost:
      log.write(level, c,
                "device missing (%s): running without buttons, open strokes end as on lost "
                "tracking; it is picked up when it appears",
                {e.status.name()});
      return true;
    case K::buttons_found:
      log.write(level, c, "device found: buttons work again");
      return true;
    case K::visitor: {
      const auto& v = e.visitor();
      log.write(level, c, "%s: visitor %u, sculpture %08x, %u journal records (end %s%s%s)",
                {session::visitor_note_name(v.note), v.visitor, v.sculpture, v.records,
                 session::sculpture_end_name(v.end), e.status.ok() ? "" : "; ",
                 e.status.ok() ? "" : e.status.name()});
      return true;
    }
    case K::refine_stopped:
      log.write(level, c,
                "journal record %u: refinement stopped, the mesh's %s is used up "
                "(station.spare_vertices); the stroke is committed and the mesh conforming, "
                "some edges stay coarser than sculpt.refine_threshold_m",
                {e.refinement_stop().sequence, capacity_text(e.refinement_stop().stop)});
      return true;
    case K::refined:
      log.write(level, c, "journal record %u refined: %u vertices added",
                {e.refinement().sequence, e.refinement().vertices_added});
      return true;
    default:
      return false;
  }
}

void log_cancelled(const SessionEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  const unsigned hand = e.hand;
  if (!e.status.ok()) {
    log.write(level, station_event_component(e),
              "hand %u cancelled (%s); model as at the last commit", {hand, e.status.name()});
  } else if (e.stroke_end().reason == input::Reason::stopped) {
    log.write(level, station_event_component(e),
              "hand %u cancelled (station stopping); model unchanged", {hand});
  } else {
    log.write(level, station_event_component(e),
              "hand %u cancelled (tracking lost too long); model unchanged", {hand});
  }
}

bool log_strokes(const SessionEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  const unsigned hand = e.hand;
  switch (e.kind) {
    case K::grab_begin:
      log.write(level, station_event_component(e), "hand %u grabbed", {hand});
      return true;
    case K::committed:
      log.write(level, station_event_component(e), "hand %u committed as journal record %u",
                {hand, e.stroke_end().sequence});
      return true;
    case K::cancelled:
      log_cancelled(e, log);
      return true;
    case K::refused:
      log.write(level, station_event_component(e), "press refused: hand %u (%s)",
                {hand, e.status.ok() ? input::reason_name(e.reasoned().reason) : e.status.name()});
      return true;
    case K::tracking_lost:
      log.write(level, station_event_component(e),
                "hand %u lost tracking; the warp holds at its last pose", {hand});
      return true;
    case K::tracking_resumed:
      log.write(level, station_event_component(e), "hand %u tracked again; the warp follows",
                {hand});
      return true;
    case K::disengaged:
      log.write(level, "stroke",
                "hand %u on the clutch (freeze held): committed as journal record %u; the hand "
                "moves freely",
                {hand, e.record().sequence});
      return true;
    case K::engaged:
      log.write(level, station_event_component(e),
                "hand %u off the clutch: warping again from where it is", {hand});
      return true;
    case K::turn_limit_reached:
      log.write(level, "stroke",
                "hand %u turned past the %.0f-degree limit; the warp holds until the hand "
                "turns back",
                {hand, degrees(e.turn_limit().limit_rad)});
      return true;
    case K::turn_limit_left:
      log.write(level, station_event_component(e),
                "hand %u back within the turn limit; the warp follows again", {hand});
      return true;
    default:
      return false;
  }
}

void log_object(const SessionEvent& e, ports::LogSink& log) {
  const LogLevel level = station_event_level(e);
  const unsigned hand = e.hand;
  switch (e.kind) {
    case K::move_begin:
      log.write(level, station_event_component(e), "hand %u moves the object", {hand});
      return;
    case K::move_committed:
      log.write(level, station_event_component(e), "hand %u moved the object (journal record %u)",
                {hand, e.record().sequence});
      return;
    case K::move_cancelled:
      log.write(level, station_event_component(e),
                "hand %u: object move cancelled (%s); the object is back",
                {hand, e.reasoned().reason == input::Reason::stopped ? "station stopping"
                                                                     : "tracking lost too long"});
      return;
    default:
      return;
  }
}

bool log_session(const SessionEvent& e, ports::LogSink& log, int storage_errno) {
  const LogLevel level = station_event_level(e);
  switch (e.kind) {
    case K::radius_set:
      log.write(level, station_event_component(e), "radius %.3f m", {e.radius().radius_m});
      return true;
    case K::radius_changed:
      log.write(level, station_event_component(e), "radius %.3f m (gesture)",
                {e.radius().radius_m});
      return true;
    case K::method_changed:
      log.write(level, station_event_component(e), "warp method %s for the next strokes",
                {math::warp_method_name(e.method().method).data()});
      return true;
    case K::symmetry_changed: {
      char label[math::kSymmetryLabelSize];
      math::symmetry_label(e.symmetry().spec, label);
      log.write(level, station_event_component(e), "symmetry %s for the next strokes", {label});
      return true;
    }
    case K::undone:
      log.write(level, station_event_component(e), "undo (journal record %u)",
                {e.record().sequence});
      return true;
    case K::redone:
      log.write(level, station_event_component(e), "redo (journal record %u)",
                {e.record().sequence});
      return true;
    case K::command_refused: {
      const auto& r = e.command_refusal();
      if (e.status.code() == StatusCode::io_error) {
        log.write(level, station_event_component(e),
                  "%s not saved: %s (%s); the model is unchanged",
                  {session::session_command_name(r.command), storage_error_text(storage_errno),
                   e.status.name()});
      } else {
        log.write(level, station_event_component(e), "%s refused (%s)",
                  {session::session_command_name(r.command), input::reason_name(r.reason)});
      }
      return true;
    }
    default:
      return false;
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

const char* station_event_component(const SessionEvent& e) {
  switch (e.kind) {
    case K::journal_recovered:
    case K::checkpoint_written:
    case K::checkpoint_failed:
    case K::history_overflow:
      return "journal";
    case K::tracker_streaming:
    case K::tracker_lost:
      return "tracker";
    case K::buttons_lost:
    case K::buttons_found:
      return "buttons";
    case K::visitor:
      return "exhibit";
    case K::refined:
    case K::refine_stopped:
      return "refine";
    case K::move_begin:
    case K::move_committed:
    case K::move_cancelled:
      return "object";
    case K::radius_set:
    case K::radius_changed:
    case K::method_changed:
    case K::symmetry_changed:
      return "sculpt";
    case K::undone:
    case K::redone:
    case K::command_refused:
      return "history";
    default:
      return "stroke";
  }
}

LogLevel station_event_level(const SessionEvent& e) {
  switch (e.kind) {
    case K::not_saved:  // the sculptor's work was lost
      return LogLevel::error;
    case K::buttons_lost:  // the station runs on and picks it up: trouble, not failure
    case K::tracker_lost:
    case K::checkpoint_failed:  // the previous one stays; start-up replays more
    case K::refine_stopped:
      return LogLevel::warning;
    case K::visitor:  // a failed archive or rotation is trouble, the rest the day's course
      return e.status.ok() ? LogLevel::notice : LogLevel::warning;
    case K::cancelled:  // the stop policy is no trouble
      return e.status.ok() && e.stroke_end().reason == input::Reason::stopped ? LogLevel::notice
                                                                              : LogLevel::warning;
    case K::move_cancelled:
      return e.reasoned().reason == input::Reason::stopped ? LogLevel::notice : LogLevel::warning;
    case K::command_refused:  // io_error: an undo/redo not saved
      return e.status.code() == StatusCode::io_error ? LogLevel::error : LogLevel::notice;
    case K::journal_recovered:
    case K::tracker_streaming:
    case K::buttons_found:
    case K::refused:
    case K::radius_set:
    case K::turn_limit_reached:
    case K::undone:
    case K::redone:
    case K::method_changed:
    case K::symmetry_changed:
    case K::history_overflow:
      return LogLevel::notice;
    case K::radius_changed:  // every step of the gesture
      return LogLevel::debug;
    case K::grab_begin:
    case K::committed:
    case K::checkpoint_written:
    case K::disengaged:
    case K::engaged:
    case K::turn_limit_left:
    case K::refined:
    case K::tracking_lost:
    case K::tracking_resumed:
    case K::move_begin:
    case K::move_committed:
      return LogLevel::info;
  }
  return LogLevel::notice;
}

void log_station_event(const SessionEvent& e, ports::LogSink& log, int storage_errno) {
  if (log_journal(e, log, storage_errno) || log_station_side(e, log) || log_strokes(e, log) ||
      log_session(e, log, storage_errno)) {
    return;
  }
  log_object(e, log);
}

}  // namespace twister::station_app
