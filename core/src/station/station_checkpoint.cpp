// Station checkpoints: every checkpoint_interval records a checkpoint is written a
// chunk per poll() (the loop never stalls on a large mesh), started only while no
// stroke or move is open and dropped when the model changes before it is complete;
// stop() writes the final one in one go.
#include <limits>

#include "twister/station/station.hpp"

namespace twister::station {

Status Station::begin_checkpoint() {
  const checkpoint::CheckpointAnchor anchor{writer_.size(), journal_records(), writer_.last_crc()};
  return checkpoint_.begin(sculpt_, anchor, base_checksum_);
}

void Station::checkpoint_step() {
  if (files_.checkpoint_out == nullptr) return;
  if (!checkpoint_.active()) {
    const std::uint64_t since = journal_records() - records_at_checkpoint_;
    if (config_.checkpoint_interval == 0 || since < config_.checkpoint_interval || sculpt_.busy()) {
      return;
    }
    if (const Status s = begin_checkpoint(); !s.ok()) {
      records_at_checkpoint_ = journal_records();  // try again one interval later
      checkpoint_failed(s);
      return;
    }
  }
  // A commit since begin() changed the model: this checkpoint would not match it.
  if (sculpt_.next_sequence() != checkpoint_.header().next_sequence) {
    checkpoint_.abort();
    ++counters_.checkpoints_restarted;
    return;
  }
  const auto done = checkpoint_.step(sculpt_, config_.checkpoint_bytes_per_poll);
  if (!done.ok()) {
    records_at_checkpoint_ = journal_records();
    checkpoint_failed(done.status());
    return;
  }
  if (*done) checkpoint_written();
}

void Station::final_checkpoint() {
  if (files_.checkpoint_out == nullptr) return;
  checkpoint_.abort();
  if (journal_records() == records_at_checkpoint_) return;  // the last one is current
  Status s = begin_checkpoint();
  if (s.ok()) {
    const auto done = checkpoint_.step(sculpt_, std::numeric_limits<std::size_t>::max());
    s = done.status();
  }
  if (s.ok()) {
    checkpoint_written();
  } else {
    checkpoint_failed(s);
  }
}

void Station::checkpoint_written() {
  const checkpoint::CheckpointHeader& h = checkpoint_.header();
  records_at_checkpoint_ = h.journal_records;
  ++counters_.checkpoints_written;
  push_event({StationEventKind::checkpoint_written, 0,
              static_cast<std::uint32_t>(h.journal_records), checkpoint::checkpoint_bytes(h),
              ok_status(), clock_.now_us()});
}

void Station::checkpoint_failed(Status s) {
  ++counters_.checkpoints_failed;
  ++counters_.journal_errors;
  push_event({StationEventKind::checkpoint_failed, 0, 0, 0, s, clock_.now_us()});
}

}  // namespace twister::station
