// VisitorFeed: one display's exhibit messages (issue 25, link protocol 7), for the
// main display and each spectator alike: the VisitorState when its phase, flags,
// visitor, sculpture or strokes change and otherwise about once a second (exhibit
// mode only), and each Notice the station posted since this display was admitted
// (NoticeBoard: refused undo / redo / commands / presses, the symmetry changed, the
// lifecycle's notes; exhibit mode on or off). Urgent queue; a message that does not
// fit is tried again next poll. No heap.
#pragma once

#include <cstdint>

#include "twister/link/link_codec.hpp"
#include "twister/ports/clock.hpp"
#include "twister/station/station_link_queues.hpp"

namespace twister::station {

class Station;

class VisitorFeed {
 public:
  // A newly admitted display: the visitor state at once, no old notice.
  void restart() { *this = VisitorFeed{}; }
  // Queues what is due on `queues` (flushing them after new notices).
  void send(const Station& station, FrameQueues& queues, ports::TimestampUs now_us);

 private:
  void send_notices(const Station& station, FrameQueues& queues);

  bool sent_ = false;
  link::VisitorState last_{};
  ports::TimestampUs last_us_ = 0;
  bool notices_synced_ = false;     // notices_sent_ set at this display's admission
  std::uint32_t notices_sent_ = 0;  // the NoticeBoard's number of the last one sent
};

}  // namespace twister::station
