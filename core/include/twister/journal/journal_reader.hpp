// JournalReader: reads the stroke journal from a ports::Storage record by record,
// checking each record's length, version, CRC and content, and in a version 2 journal
// its identity and sequence (journal_format.hpp). The first record that is torn
// (power cut mid-append) or corrupt ends the readable journal: it and everything
// after it is reported (data_loss) and never returned; truncate_tail() cuts it off.
// No allocation: one record buffer inside the reader.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

class JournalReader {
 public:
  explicit JournalReader(ports::Storage& storage) : storage_(storage) {}

  // Checks the file header and positions before the first record. An empty file
  // is a valid empty journal; a file shorter than the header is a torn header
  // (next() reports it). data_loss: the file is not a journal (wrong magic, or a
  // version 2 header whose CRC does not match; it is left alone). not_supported: a
  // journal of a newer format version (left alone). io_error: storage failure.
  Status open();
  // The file's format (after open(); version 1 for an empty file).
  const JournalFormat& format() const { return format_; }
  // What open() found in the file header.
  HeaderCheck header() const { return header_; }

  // Continues reading at `offset`, the start of a record (e.g. the end of the records
  // a checkpoint stands for); the sequence check takes the next record's as right. out_of_range:
  // before the first record or past the end; failed_precondition: open() did not succeed.
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

  // Cuts a reported torn tail and syncs. An empty or torn file header is cut to zero
  // length (the writer writes a fresh header). data_loss, nothing cut: the problem is
  // a complete record that is refused (may_be_torn() is false for it).
  Status truncate_tail();

 private:
  Result<JournalRecord> fail(TailProblem problem);

  ports::Storage& storage_;
  bool opened_ = false;
  std::uint64_t file_size_ = 0;
  std::uint64_t good_end_ = 0;
  TailProblem problem_ = TailProblem::none;
  JournalFormat format_{};
  HeaderCheck header_ = HeaderCheck::ok;
  SequenceCheck order_{};
  std::array<std::byte, kMaxRecordBytes> buffer_{};
};

}  // namespace twister::journal
