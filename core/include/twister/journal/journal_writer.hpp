// JournalWriter: appends records to the stroke journal through a ports::Storage and
// makes each durable (Storage::sync, fsync on the POSIX backend) before returning.
// Open it on a recovered journal (JournalReader read to the end, tail truncated).
// No allocation: one record buffer inside the writer.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

class JournalWriter {
 public:
  explicit JournalWriter(ports::Storage& storage) : storage_(storage) {}

  // Writes the file header to an empty file (and syncs). io_error: storage failed.
  // data_loss: the file is non-empty and not a journal.
  Status open();

  // Encodes, appends and syncs one record. invalid_argument: the record is invalid
  // (nothing written). io_error: the append or sync failed; the writer then tries
  // to cut the partial record off again, and when that fails too it refuses every
  // further append (failed_precondition) so no good record lands after a torn one.
  Status append(const JournalRecord& record);

  // After a failure that left the writer broken: cuts the file back to the end of
  // the last good record and syncs; then appends work again. io_error: still
  // failing (still broken); failed_precondition: not opened. No-op when healthy.
  Status repair();

  bool healthy() const { return opened_ && !broken_; }
  std::uint64_t size() const { return size_; }
  // Records appended (and synced) since open().
  std::uint64_t appended() const { return appended_; }
  // The CRC field of the last record in the file (0 when there is none): with size()
  // it pins a position in this journal (a checkpoint's anchor).
  std::uint32_t last_crc() const { return last_crc_; }

 private:
  ports::Storage& storage_;
  bool opened_ = false;
  bool broken_ = false;
  std::uint64_t size_ = 0;
  std::uint64_t appended_ = 0;
  std::uint32_t last_crc_ = 0;
  std::array<std::byte, kMaxRecordBytes> buffer_{};
};

}  // namespace twister::journal
