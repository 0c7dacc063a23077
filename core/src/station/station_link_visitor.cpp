// VisitorFeed (station_link_visitor.hpp): one display's visitor state and notices.
#include "twister/station/station_link_visitor.hpp"

#include <algorithm>

#include "twister/station/station.hpp"

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

void VisitorFeed::send(const Station& station, FrameQueues& queues, ports::TimestampUs now_us) {
  if (station.visitor_view_enabled()) {
    const link::VisitorState s = to_link(station.visitor_view());
    const bool changed = s.phase != last_.phase || s.flags != last_.flags ||
                         s.visitor != last_.visitor || s.sculpture != last_.sculpture ||
                         s.strokes != last_.strokes;
    if ((!sent_ || changed || now_us - last_us_ >= 1'000'000) && queues.urgent(s)) {
      sent_ = true;
      last_ = s;
      last_us_ = now_us;
    }
  }
  send_notices(station, queues);
}

void VisitorFeed::send_notices(const Station& station, FrameQueues& queues) {
  const NoticeBoard& board = station.notices();
  if (!notices_synced_) {  // a newly admitted display: nothing old
    notices_synced_ = true;
    notices_sent_ = board.posted();
  }
  // Those the ring no longer holds (more than kCapacity in one poll) are skipped.
  std::uint32_t next = std::max(notices_sent_ + 1, board.oldest());
  for (; next <= board.posted(); ++next) {
    if (!queues.urgent(board.at(next))) break;  // the rest next poll
  }
  if (next - 1 == notices_sent_) return;
  notices_sent_ = next - 1;
  queues.flush();
}

}  // namespace twister::station
