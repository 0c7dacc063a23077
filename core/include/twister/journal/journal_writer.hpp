// JournalWriter: appends records to the stroke journal through a ports::Storage and
// makes each durable (Storage::sync, fsync on the POSIX backend) before returning.
// Open it on a recovered journal (JournalReader read to the end, tail truncated).
// No allocation: one record buffer inside the writer.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

class JournalWriter {
 public:
  explicit JournalWriter(ports::Storage& storage) : storage_(storage) {}

  // The identity a new journal gets (version 2 header and records); the composition
  // root picks a random one so records of two journals never pass for each other.
  void set_new_journal_id(std::uint32_t id) { new_id_ = id; }

  // Writes the file header of a new version 2 journal to an empty file (and syncs);
  // a non-empty journal is appended to in its own format (version 1 stays version 1).
  // io_error: storage failed (storage's errno says why, e.g. a full disk).
  // data_loss: the file is non-empty and not a journal (or its header is torn or
  // damaged); not_supported: a journal of a newer format version.
  Status open();

  // Encodes (in the file's format), appends and syncs one record. The caller numbers
  // records 0, 1, 2, ... (SessionHistory does); a version 2 reader refuses anything else.
  // invalid_argument: the record is invalid (nothing written). io_error: the append or sync failed;
  // the writer then tries to cut the partial record off again, and when that fails too it refuses
  // every further append (failed_precondition) so no good record lands after a torn one.
  Status append(const JournalRecord& record);

  // After a failure that left the writer broken: cuts the file back to the end of
  // the last good record and syncs; then appends work again. io_error: still
  // failing (still broken); failed_precondition: not opened. No-op when healthy.
  Status repair();

  // Rotation (issue 25, exhibit mode): the journal's bytes are durably archived
  // elsewhere; the file is cut to nothing and a new journal with identity `id` begins
  // in it (header written and synced), as open() does for an empty file. io_error:
  // the cut or the header failed (opened() is then false: call open() again later;
  // a failed cut leaves the old journal as it was).
  Status restart(std::uint32_t id);

  bool healthy() const { return opened_ && !broken_; }
  bool opened() const { return opened_; }
  std::uint64_t size() const { return size_; }
  // Records appended (and synced) since open().
  std::uint64_t appended() const { return appended_; }
  // The file's format (after open()).
  const JournalFormat& format() const { return format_; }
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
  std::uint32_t new_id_ = 0;
  JournalFormat format_{};
  std::array<std::byte, kMaxRecordBytes> buffer_{};
};

}  // namespace twister::journal
