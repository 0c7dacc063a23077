#include "twister/station/notice_board.hpp"

#include <algorithm>

#include "twister/base/assert.hpp"

namespace twister::station {
namespace {

using session::SessionEventKind;

std::uint8_t byte_of(input::Reason reason) { return static_cast<std::uint8_t>(reason); }

bool visitor_notice(const session::payload::Visitor& v, link::Notice& out) {
  using N = session::VisitorNote;
  switch (v.note) {
    case N::archived:
      out = {link::NoticeCode::sculpture_archived,
             static_cast<std::uint8_t>(std::min<std::uint32_t>(v.visitor, 255))};
      return true;
    case N::archive_failed:
    case N::rotate_failed:
      out = {link::NoticeCode::archive_failed, 0};
      return true;
    case N::disk_full:
      out = {link::NoticeCode::disk_full, 0};
      return true;
    case N::undone:
      out = {link::NoticeCode::new_sculpture_undone, 0};
      return true;
    case N::refused:
      out = {link::NoticeCode::nothing_to_act_on, byte_of(input::Reason::none)};
      return true;
    case N::began:
    case N::ended:
      return false;
  }
  return false;
}

}  // namespace

bool notice_for(const session::SessionEvent& event, link::Notice& out) {
  switch (event.kind) {
    case SessionEventKind::command_refused: {
      const session::payload::CommandRefusal& r = event.command_refusal();
      out.detail = byte_of(r.reason);
      out.code = r.command == session::SessionCommandKind::undo ? link::NoticeCode::undo_refused
                 : r.command == session::SessionCommandKind::redo
                     ? link::NoticeCode::redo_refused
                     : link::NoticeCode::nothing_to_act_on;
      return true;
    }
    case SessionEventKind::refused:
      out = {link::NoticeCode::nothing_to_act_on, byte_of(event.reasoned().reason)};
      return true;
    case SessionEventKind::symmetry_changed:
      out = {link::NoticeCode::symmetry_changed,
             static_cast<std::uint8_t>(event.symmetry().spec.kind)};
      return true;
    case SessionEventKind::visitor:
      return visitor_notice(event.visitor(), out);
    default:
      return false;
  }
}

void NoticeBoard::see(const session::SessionEvent& event) {
  link::Notice n;
  if (notice_for(event, n)) post(n);
}

void NoticeBoard::post(const link::Notice& notice) {
  ring_[posted_ % kCapacity] = notice;
  ++posted_;
}

const link::Notice& NoticeBoard::at(std::uint32_t number) const {
  TWISTER_ASSERT(number >= oldest() && number <= posted_ && number > 0);
  return ring_[(number - 1) % kCapacity];
}

}  // namespace twister::station
