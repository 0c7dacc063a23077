// JournalReader: reads the stroke journal from a ports::Storage record by record,
// checking each record's length, version and CRC. The first record that is torn
// (power cut mid-append) or corrupt ends the readable journal: it and everything
// after it is reported (data_loss) and never returned; truncate_tail() cuts it off.
// No allocation: one record buffer inside the reader.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

enum class TailProblem : std::uint8_t {
  none = 0,
  torn_header,  // the file ends inside a record header (or the file header)
  torn_record,  // the file ends inside a record's payload or CRC
  bad_length,   // payload length above kMaxPayloadBytes or reserved bits set
  bad_crc,      // CRC mismatch
  bad_payload,  // CRC fine but the content is invalid (version, type, fields)
};
const char* tail_problem_name(TailProblem problem);

class JournalReader {
 public:
  explicit JournalReader(ports::Storage& storage) : storage_(storage) {}

  // Checks the file header and positions before the first record. An empty file
  // is a valid empty journal; a file shorter than the header is a torn header
  // (next() reports it). data_loss: the file is not a journal (wrong magic or
  // version; it is left alone). io_error: storage failure.
  Status open();

  // Continues reading at `offset`, the start of a record (e.g. the end of the records
  // a checkpoint stands for). out_of_range: before the first record or past the end;
  // failed_precondition: open() did not succeed.
  Status seek(std::uint64_t offset);

  // Next good record. unavailable: clean end of the journal. data_loss: a torn or
  // corrupt tail starts at good_end() (see problem()); nothing from it is returned.
  // io_error: storage failure. failed_precondition: open() did not succeed.
  Result<JournalRecord> next();

  // Offset just after the last good record (or the file header).
  std::uint64_t good_end() const { return good_end_; }
  // Bytes after good_end() (the tail that truncate_tail() drops).
  std::uint64_t tail_bytes() const { return file_size_ - good_end_; }
  TailProblem problem() const { return problem_; }

  // Cuts a reported torn/corrupt tail and syncs. An empty or torn file header is
  // cut to zero length (the writer writes a fresh header).
  Status truncate_tail();

 private:
  Result<JournalRecord> fail(TailProblem problem);

  ports::Storage& storage_;
  bool opened_ = false;
  std::uint64_t file_size_ = 0;
  std::uint64_t good_end_ = 0;
  TailProblem problem_ = TailProblem::none;
  std::array<std::byte, kMaxRecordBytes> buffer_{};
};

}  // namespace twister::journal
