#include "station_log.hpp"

#include <numbers>

#include "twister/input/interaction_machine.hpp"
#include "twister/input/session_command.hpp"
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
  return value < input::kSessionCommandKindCount
             ? input::session_command_name(static_cast<input::SessionCommandKind>(value))
             : "?";
}

// Trouble and the station's own life (tracker, journal) first.
bool log_station_side(const StationEvent& e, ports::LogSink& log) {
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
    case StationEventKind::tracker_streaming:
      log.write(level, "tracker", "streaming (start-up #%u)", {e.value});
      return true;
    case StationEventKind::tracker_lost:
      log.write(level, "tracker",
                "lost (unplugged, silent or garbled); waiting and re-initialising");
      return true;
    case StationEventKind::journal_error:
      log.write(level, "journal", "append failed (%s); stroke not recorded", {e.status.name()});
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
      if (e.status.ok()) {
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

void log_session(const StationEvent& e, ports::LogSink& log) {
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
      log.write(level, "history", "%s refused (%s)",
                {command_text(e.value), reason_text(e.detail)});
      return;
    default:
      return;
  }
}

}  // namespace

LogLevel station_event_level(const StationEvent& e) {
  switch (e.kind) {
    case StationEventKind::journal_error:
      return LogLevel::error;
    case StationEventKind::button_source_error:  // reopened by the loop: trouble, not failure
    case StationEventKind::tracker_lost:
    case StationEventKind::stroke_cancelled:
    case StationEventKind::refinement_stopped:
      return LogLevel::warning;
    case StationEventKind::journal_recovered:
    case StationEventKind::tracker_streaming:
    case StationEventKind::refused:
    case StationEventKind::radius_set:
    case StationEventKind::turn_limit_reached:
    case StationEventKind::undone:
    case StationEventKind::redone:
    case StationEventKind::method_changed:
    case StationEventKind::command_refused:
      return LogLevel::notice;
    case StationEventKind::stroke_begin:
    case StationEventKind::stroke_committed:
    case StationEventKind::hand_disengaged:
    case StationEventKind::hand_engaged:
    case StationEventKind::turn_limit_left:
    case StationEventKind::stroke_refined:
      return LogLevel::info;
  }
  return LogLevel::notice;
}

void log_station_event(const StationEvent& e, ports::LogSink& log) {
  if (log_station_side(e, log)) return;
  log_strokes(e, log);
  log_session(e, log);
}

}  // namespace twister::station_app
