// StationLink's exhibit messages (issue 25, link protocol 7): the VisitorState when its
// phase, flags, visitor, sculpture or strokes change and otherwise about once a second
// (the time left then goes with it), and the lifecycle's newest note as a Notice
// (sculpture_archived with the visitor number as detail, archive_failed, disk_full,
// new_sculpture_undone, nothing_to_act_on). Urgent queue; a message that does not fit
// is tried again next poll. Nothing is sent with exhibit mode off.
#include <algorithm>

#include "twister/station/station.hpp"
#include "twister/station/station_link.hpp"

namespace twister::station {
namespace {

link::VisitorState to_link(const VisitorView& v) {
  link::VisitorState s;
  s.phase = static_cast<link::VisitorPhase>(v.phase);
  s.flags = static_cast<std::uint8_t>(
      ((v.flags & kVisitorFlagResetUndoable) != 0 ? link::kVisitorResetUndoable : 0) |
      ((v.flags & kVisitorFlagArchiveFailed) != 0 ? link::kVisitorArchiveFailed : 0) |
      ((v.flags & kVisitorFlagDiskFull) != 0 ? link::kVisitorDiskFull : 0));
  s.visitor = v.visitor;
  s.sculpture = v.sculpture;
  s.strokes = v.records;
  s.idle_left_s = v.idle_left_s;
  s.grace_left_s = v.grace_left_s;
  return s;
}

bool notice_of(session::VisitorNote note, link::NoticeCode& code) {
  using N = session::VisitorNote;
  switch (note) {
    case N::archived:
      code = link::NoticeCode::sculpture_archived;
      return true;
    case N::archive_failed:
    case N::rotate_failed:
      code = link::NoticeCode::archive_failed;
      return true;
    case N::disk_full:
      code = link::NoticeCode::disk_full;
      return true;
    case N::undone:
      code = link::NoticeCode::new_sculpture_undone;
      return true;
    case N::refused:
      code = link::NoticeCode::nothing_to_act_on;
      return true;
    case N::began:
    case N::ended:
      return false;
  }
  return false;
}

}  // namespace

void StationLink::send_visitor(const Station& station, ports::TimestampUs now_us) {
  if (!admitted() || !station.visitor_view_enabled()) return;
  const link::VisitorState s = to_link(station.visitor_view());
  const link::VisitorState& last = visitor_.last;
  const bool changed = s.phase != last.phase || s.flags != last.flags ||
                       s.visitor != last.visitor || s.sculpture != last.sculpture ||
                       s.strokes != last.strokes;
  if (!visitor_.sent) visitor_.told_seq = station.visitor_told().seq;  // nothing old
  if (!visitor_.sent || changed || now_us - visitor_.last_us >= 1'000'000) {
    if (queues_.urgent(s)) {
      visitor_.sent = true;
      visitor_.last = s;
      visitor_.last_us = now_us;
    }
  }
  const StationExhibit::Told& told = station.visitor_told();
  if (told.seq == visitor_.told_seq) return;
  link::Notice n;
  if (notice_of(told.note, n.code)) {
    n.detail = static_cast<std::uint8_t>(std::min<std::uint32_t>(told.visitor, 255));
    if (!queues_.urgent(n)) return;  // next poll
  }
  visitor_.told_seq = told.seq;
  queues_.flush();
}

}  // namespace twister::station
