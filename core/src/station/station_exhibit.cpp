// Exhibit mode (issue 25): StationExhibit, and the Station's side of the visitor
// lifecycle: each poll one lifecycle step; at the end of the grace the sculpture is
// archived (SculptureArchive: durable under its final name, or nothing), then the
// journal rotates (cut and a new header: JournalWriter::restart) and the model is reset
// to the base. A failed archive changes nothing (tried again after retry_us); a failed
// rotation after a good archive is retried (strokes are reported not saved meanwhile).
// The on-disk protocol and its crash points: docs/reliability.md "Exhibit mode".
#include "twister/station/station_exhibit.hpp"

#include "twister/station/station.hpp"

namespace twister::station {

void StationExhibit::start(bool has_sculpture, std::uint32_t visitors_today,
                           ports::TimestampUs now_us) {
  visitor_ = visitors_today + (has_sculpture ? 1u : 0u);
  began_us_ = now_us;
  ended_us_ = now_us;
  now_us_ = now_us;
  counters_.ended_today = visitors_today;
  life_.start(has_sculpture, now_us);
}

void StationExhibit::feed_edge(const ports::ButtonEdge& edge) {
  if (edge.line >= 16) return;
  const auto bit = static_cast<std::uint16_t>(1u << edge.line);
  levels_ = static_cast<std::uint16_t>(edge.pressed ? (levels_ | bit) : (levels_ & ~bit));
}

void Station::note(session::VisitorNote what, ports::TimestampUs now_us, Status status) {
  session::payload::Visitor v;
  v.note = what;
  v.end = exhibit_.life().end();
  v.visitor = exhibit_.visitor();
  v.sculpture = writer_.format().id;
  v.records = journal_records();
  emit(session::make_event(session::SessionEventKind::visitor, 0, v, status), now_us);
}

Status Station::submit(const session::SessionCommand& command) {
  if (exhibit_.enabled()) {
    if (command.kind == session::SessionCommandKind::new_sculpture) return new_sculpture();
    if (command.kind == session::SessionCommandKind::undo_new_sculpture) {
      return undo_new_sculpture();
    }
  }
  return sculpt_.submit(command);
}

void Station::step_exhibit(ports::TimestampUs now_us) {
  if (!exhibit_.enabled()) return;
  exhibit_.now_us() = now_us;
  // A new journal that could not be begun (full disk): tried again now and then.
  if (!writer_.opened() && now_us >= exhibit_.journal_retry_us()) {
    if (!writer_.open().ok()) exhibit_.journal_retry_us() = now_us + 1'000'000;
  }
  session::VisitorInputs in;
  in.active = sculpt_.busy();
  in.chord_held = exhibit_.chord_held();
  for (std::uint8_t h = 0; h < 2; ++h) {
    in.tracked[h] = tracker_.hand_valid(h, now_us);
    const glm::dvec3 p = tracker_.hand_pose(h).origin;
    in.hand_m[h] = {p.x, p.y, p.z};
  }
  act(exhibit_.life().step(in, now_us), now_us);
}

void Station::act(session::VisitorAction action, ports::TimestampUs now_us) {
  using A = session::VisitorAction;
  using N = session::VisitorNote;
  switch (action) {
    case A::none:
      return;
    case A::began:
      exhibit_.next_visitor(now_us);
      note(N::began, now_us);
      return;
    case A::ended:
      exhibit_.set_ended(now_us);
      note(N::ended, now_us);
      return;
    case A::undone:
      ++exhibit_.counters().undone;
      note(N::undone, now_us);
      return;
    case A::refused:
      ++exhibit_.counters().refused;
      note(N::refused, now_us);
      return;
    case A::archive:
      end_sculpture(now_us);
      return;
  }
}

void Station::end_sculpture(ports::TimestampUs now_us) {
  if (journal_records() == 0) {  // a visitor who made nothing: nothing to keep
    exhibit_.life().archived(true, now_us);
    return;
  }
  SculptureSummary summary;
  summary.sculpture = writer_.format().id;
  summary.visitor = exhibit_.visitor();
  summary.records = journal_records();
  summary.checksum = sculpt_.mesh().checksum();
  summary.end = exhibit_.life().end();
  summary.began_us = exhibit_.began_us();
  summary.ended_us = exhibit_.ended_us();
  summary.now_us = now_us;
  const ArchiveOutcome out = files_.archive->archive(summary, storage_, writer_.size(),
                                                     sculpt_.mesh(), sculpt_.object_pose());
  if (!out.status.ok()) {
    ++exhibit_.counters().archive_failures;
    if (out.disk_full) ++exhibit_.counters().disk_full;
    exhibit_.trouble() = static_cast<std::uint8_t>(kVisitorFlagArchiveFailed |
                                                   (out.disk_full ? kVisitorFlagDiskFull : 0));
    exhibit_.life().archived(false, now_us);
    note(out.disk_full ? session::VisitorNote::disk_full : session::VisitorNote::archive_failed,
         now_us, out.status);
    return;
  }
  exhibit_.trouble() = 0;
  ++exhibit_.counters().archived;
  if (const Status rotated = rotate_journal(now_us); !rotated.ok()) {
    ++exhibit_.counters().rotate_failures;
    note(session::VisitorNote::rotate_failed, now_us, rotated);
    if (writer_.size() > 0 && writer_.opened()) {
      // The cut failed: the journal still holds the sculpture (archived; the archive
      // is reused next time). Nothing was reset: try the whole end again later.
      exhibit_.life().archived(false, now_us);
      return;
    }
  }
  ++exhibit_.counters().ended_today;
  exhibit_.life().archived(true, now_us);
  // Told about the sculpture archived (the journal is the new one by now).
  session::payload::Visitor v;
  v.note = session::VisitorNote::archived;
  v.end = summary.end;
  v.visitor = summary.visitor;
  v.sculpture = summary.sculpture;
  v.records = summary.records;
  emit(session::make_event(session::SessionEventKind::visitor, 0, v, ok_status()), now_us);
}

Status Station::rotate_journal(ports::TimestampUs now_us) {
  const Status restarted = writer_.restart(files_.archive->next_journal_id());
  if (!restarted.ok() && writer_.opened()) return restarted;  // not cut: unchanged
  // The journal is empty (or holds only the new header): the model follows it.
  (void)sculpt_.reset_model(*files_.base_model);
  records_at_start_ = 0;
  checkpoints_.reset(checkpoints_.base_checksum(), 0);
  exhibit_.journal_retry_us() = now_us + 1'000'000;
  return restarted;
}

Status Station::new_sculpture() {
  if (!started_ || !exhibit_.enabled()) return StatusCode::failed_precondition;
  const ports::TimestampUs now_us = clock_.now_us();
  const session::VisitorAction a = exhibit_.life().request_new(now_us);
  act(a, now_us);
  return a == session::VisitorAction::ended ? ok_status() : Status(StatusCode::failed_precondition);
}

Status Station::undo_new_sculpture() {
  if (!started_ || !exhibit_.enabled()) return StatusCode::failed_precondition;
  const ports::TimestampUs now_us = clock_.now_us();
  const session::VisitorAction a = exhibit_.life().request_undo(now_us);
  act(a, now_us);
  return a == session::VisitorAction::undone ? ok_status()
                                             : Status(StatusCode::failed_precondition);
}

VisitorView Station::visitor_view() const {
  VisitorView v;
  const session::VisitorLifecycle& life = exhibit_.life();
  const ports::TimestampUs now_us = exhibit_.now_us();
  v.phase = life.phase();
  v.flags = exhibit_.trouble();
  if (life.undoable()) v.flags |= kVisitorFlagResetUndoable;
  v.visitor = exhibit_.visitor();
  v.sculpture = writer_.format().id;
  v.records = journal_records();
  // Whole tenths of a second, so the view changes at most ten times a second.
  const auto tenths = [](ports::TimestampUs us) {
    const ports::TimestampUs whole = us / 100'000;  // truncated on purpose
    return static_cast<float>(whole) / 10.0F;
  };
  v.idle_left_s = tenths(life.idle_left_us(now_us));
  v.grace_left_s = tenths(life.grace_left_us(now_us));
  return v;
}

}  // namespace twister::station
