// StationLink's exhibit messages (issue 25, link protocol 7): the VisitorState when its
// phase, flags, visitor, sculpture or strokes change and otherwise about once a second
// (the time left then goes with it; exhibit mode only), and each Notice the station
// posted since the last poll (NoticeBoard: refused undo / redo / commands / presses,
// the symmetry changed, the lifecycle's notes; exhibit mode on or off). Urgent queue;
// a message that does not fit is tried again next poll.
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

}  // namespace

void StationLink::send_visitor(const Station& station, ports::TimestampUs now_us) {
  if (!admitted()) return;
  if (station.visitor_view_enabled()) {
    const link::VisitorState s = to_link(station.visitor_view());
    const link::VisitorState& last = visitor_.last;
    const bool changed = s.phase != last.phase || s.flags != last.flags ||
                         s.visitor != last.visitor || s.sculpture != last.sculpture ||
                         s.strokes != last.strokes;
    if (!visitor_.sent || changed || now_us - visitor_.last_us >= 1'000'000) {
      if (queues_.urgent(s)) {
        visitor_.sent = true;
        visitor_.last = s;
        visitor_.last_us = now_us;
      }
    }
  }
  send_notices(station);
}

void StationLink::send_notices(const Station& station) {
  const NoticeBoard& board = station.notices();
  if (!visitor_.notices_synced) {  // a newly admitted display: nothing old
    visitor_.notices_synced = true;
    visitor_.notices_sent = board.posted();
  }
  // Those the ring no longer holds (more than kCapacity in one poll) are skipped.
  std::uint32_t next = std::max(visitor_.notices_sent + 1, board.oldest());
  for (; next <= board.posted(); ++next) {
    if (!queues_.urgent(board.at(next))) break;  // the rest next poll
  }
  if (next - 1 == visitor_.notices_sent) return;
  visitor_.notices_sent = next - 1;
  queues_.flush();
}

}  // namespace twister::station
