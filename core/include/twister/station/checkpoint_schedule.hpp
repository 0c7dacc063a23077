// CheckpointSchedule: when the station writes checkpoints. Every `interval` journal
// records a checkpoint is written a chunk per poll (the loop never stalls on a large
// mesh), started only while no stroke or move is open and dropped (counted as
// restarted) when the model changes before it is complete; finish() writes the final
// one in one go at stop. Reports checkpoint_written / checkpoint_failed events. The
// anchor (journal size, records, last CRC) is the journal as it stands at the call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/ports/file_sink.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/session/session_events.hpp"

namespace twister::station {

class CheckpointSchedule {
 public:
  // `out` null: no checkpoints are written. interval 0: only at stop.
  CheckpointSchedule(ports::FileSink* out, std::uint32_t interval, std::size_t bytes_per_poll);

  // start(): the initial model's checksum (before any record) and the records the
  // checkpoint start-up used already hold.
  void reset(std::uint64_t base_checksum, std::uint64_t records_at_checkpoint);
  std::uint64_t base_checksum() const { return base_checksum_; }

  // One chunk, when one is due or under way.
  std::optional<session::SessionEvent> step(const session::SculptSession& sculpt,
                                            const checkpoint::CheckpointAnchor& anchor);
  // The final checkpoint (when the journal grew since the last one), in one go.
  std::optional<session::SessionEvent> finish(const session::SculptSession& sculpt,
                                              const checkpoint::CheckpointAnchor& anchor);
  std::uint64_t restarted() const { return restarted_; }

 private:
  session::SessionEvent written();
  session::SessionEvent failed(Status s, const checkpoint::CheckpointAnchor& anchor);

  ports::FileSink* out_;
  checkpoint::CheckpointWriter writer_;
  std::uint32_t interval_;
  std::size_t bytes_per_poll_;
  std::uint64_t base_checksum_ = 0;          // the initial model's, before any record
  std::uint64_t records_at_checkpoint_ = 0;  // records the last checkpoint holds
  std::uint64_t restarted_ = 0;              // the model changed while one was written
};

}  // namespace twister::station
