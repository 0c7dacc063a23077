#include "twister/station/checkpoint_schedule.hpp"

#include <limits>

namespace twister::station {

using session::SessionEvent;
using session::SessionEventKind;

CheckpointSchedule::CheckpointSchedule(ports::FileSink* out, std::uint32_t interval,
                                       std::size_t bytes_per_poll)
    : out_(out), writer_(out), interval_(interval), bytes_per_poll_(bytes_per_poll) {}

void CheckpointSchedule::reset(std::uint64_t base_checksum, std::uint64_t records_at_checkpoint) {
  writer_.abort();
  base_checksum_ = base_checksum;
  records_at_checkpoint_ = records_at_checkpoint;
}

std::optional<SessionEvent> CheckpointSchedule::step(const session::SculptSession& sculpt,
                                                     const checkpoint::CheckpointAnchor& anchor) {
  if (out_ == nullptr) return std::nullopt;
  if (!writer_.active()) {
    const std::uint64_t since = anchor.journal_records - records_at_checkpoint_;
    if (interval_ == 0 || since < interval_ || sculpt.busy()) return std::nullopt;
    if (const Status s = writer_.begin(sculpt, anchor, base_checksum_); !s.ok()) {
      return failed(s, anchor);  // tried again one interval later
    }
  }
  // A commit since begin() changed the model: this checkpoint would not match it.
  if (sculpt.next_sequence() != writer_.header().next_sequence) {
    writer_.abort();
    ++restarted_;
    return std::nullopt;
  }
  const auto done = writer_.step(sculpt, bytes_per_poll_);
  if (!done.ok()) return failed(done.status(), anchor);
  if (*done) return written();
  return std::nullopt;
}

std::optional<SessionEvent> CheckpointSchedule::finish(const session::SculptSession& sculpt,
                                                       const checkpoint::CheckpointAnchor& anchor) {
  if (out_ == nullptr) return std::nullopt;
  writer_.abort();
  if (anchor.journal_records == records_at_checkpoint_) return std::nullopt;  // current
  Status s = writer_.begin(sculpt, anchor, base_checksum_);
  if (s.ok()) {
    const auto done = writer_.step(sculpt, std::numeric_limits<std::size_t>::max());
    s = done.status();
  }
  if (s.ok()) return written();
  return failed(s, anchor);
}

SessionEvent CheckpointSchedule::written() {
  const checkpoint::CheckpointHeader& h = writer_.header();
  records_at_checkpoint_ = h.journal_records;
  return session::make_event(
      SessionEventKind::checkpoint_written, 0,
      session::payload::CheckpointWritten{static_cast<std::uint32_t>(h.journal_records),
                                          checkpoint::checkpoint_bytes(h)});
}

SessionEvent CheckpointSchedule::failed(Status s, const checkpoint::CheckpointAnchor& anchor) {
  records_at_checkpoint_ = anchor.journal_records;  // try again one interval later
  return session::make_event(SessionEventKind::checkpoint_failed, 0, {}, s);
}

}  // namespace twister::station
