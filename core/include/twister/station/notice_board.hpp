// NoticeBoard: what the display shows briefly about why nothing happened or what just
// did (link message `notice`, protocol 7; issue 25 "feedback for every refusal"). The
// station shows every event it emits to the board (Station::emit, through EventQueue);
// the board keeps the newest kCapacity notices those events mean, numbered from 1, and
// StationLink sends the ones its display has not had. Exhibit mode on or off alike.
//   command_refused undo / redo      -> undo_refused / redo_refused, detail the reason
//                                       (input::Reason: busy, nothing_to_undo / _redo;
//                                       none: its record could not be saved)
//   command_refused, another command -> nothing_to_act_on, detail the reason (busy: a
//                                       stroke is open; not_available: off here)
//   refused (a press: grab, move,    -> nothing_to_act_on, detail the reason (no_tracking,
//   radius gesture)                     same_point, hand_busy, object_busy,
//                                       hands_too_close; none: the warp plan refused it)
//   symmetry_changed                 -> symmetry_changed, detail the group's kind
//   visitor (the lifecycle's notes)  -> archived (detail: the visitor number, at most
//                                       255), archive_failed (also rotate_failed),
//                                       disk_full, new_sculpture_undone;
//                                       refused -> nothing_to_act_on, detail none
// No other event makes a notice. Plain data, no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/link/link_message.hpp"
#include "twister/session/session_events.hpp"

namespace twister::station {

// The notice `event` means for the display. false: none.
bool notice_for(const session::SessionEvent& event, link::Notice& out);

class NoticeBoard {
 public:
  static constexpr std::size_t kCapacity = 8;

  // Posts the notice `event` means, if any.
  void see(const session::SessionEvent& event);
  void post(const link::Notice& notice);
  // Notices posted so far; they are numbered 1..posted().
  std::uint32_t posted() const { return posted_; }
  // The oldest number still held (posted() + 1 when none is).
  std::uint32_t oldest() const {
    return posted_ > kCapacity ? posted_ - static_cast<std::uint32_t>(kCapacity) + 1 : 1;
  }
  // Notice `number` (oldest() <= number <= posted()).
  const link::Notice& at(std::uint32_t number) const;

 private:
  std::array<link::Notice, kCapacity> ring_{};
  std::uint32_t posted_ = 0;
};

}  // namespace twister::station
