// JournalScanner: walks a journal file like JournalReader, record by record, but does
// not stop at a damaged record: it reports the damaged byte range and resynchronises
// on the next offset where a whole valid record starts (length, version, reserved
// bytes, CRC and content all check; a random match needs a 32-bit CRC to agree).
// survey_journal() uses it to tell a torn tail (damage an interrupted append can leave,
// with no valid or refused record after it: safe to cut) from corruption (valid
// records after the damage, or any refused record: refuse, never cut); `twister journal
// check|salvage` use it to list and keep every valid record. No allocation: a 4 KiB read window
// inside the scanner. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

struct ScanItem {
  enum class Kind : std::uint8_t { record, damage };
  Kind kind = Kind::record;
  std::uint64_t offset = 0;                 // where the record or the damaged range starts
  std::uint64_t bytes = 0;                  // its length in the file
  TailProblem problem = TailProblem::none;  // damage: what was wrong at `offset`
  // record: the decoded record; damage refused for its order alone
  // (is_order_problem(problem)): the record, which decodes.
  JournalRecord record{};
};

class JournalScanner {
 public:
  explicit JournalScanner(ports::Storage& storage) : storage_(storage) {}

  // Checks the file header (as JournalReader::open). An empty file scans empty; a
  // file that is a prefix of the header is one damaged range (torn_header).
  // data_loss: not a journal or a damaged version 2 header (left alone); not_supported:
  // a newer format version (header() says which). io_error: storage failure.
  Status open();
  const JournalFormat& format() const { return format_; }
  HeaderCheck header() const { return header_; }
  // The next record or damaged range, in file order; together they cover every
  // byte after the file header exactly once. unavailable: the end.
  // failed_precondition: open() did not succeed. io_error: storage failure.
  Result<ScanItem> next();

  std::uint64_t file_size() const { return file_size_; }

 private:
  // The record starting at `offset`, or the problem that keeps it from being one.
  TailProblem parse_at(std::uint64_t offset, JournalRecord& record, std::size_t& total);
  // Where the damage at pos_ ends: the next offset where a complete CRC-valid record
  // starts, or the end of the file.
  Result<std::uint64_t> resync();
  // Makes the window hold [offset, offset + bytes) (bytes <= window size, in the file).
  bool load(std::uint64_t offset, std::size_t bytes);

  ports::Storage& storage_;
  bool opened_ = false;
  bool storage_failed_ = false;
  std::uint64_t file_size_ = 0;
  std::uint64_t pos_ = 0;
  JournalFormat format_{};
  HeaderCheck header_ = HeaderCheck::ok;
  SequenceCheck order_{};
  std::uint64_t window_offset_ = 0;
  std::size_t window_bytes_ = 0;
  std::array<std::byte, 4096> window_{};
};

// What a journal file holds, from a scan of all of it.
struct JournalSurvey {
  std::uint64_t file_size = 0;
  std::uint64_t records = 0;   // valid records before the first damage
  std::uint64_t good_end = 0;  // end of those (0 for an empty file or a torn file header)
  bool has_records = false;
  std::uint32_t last_sequence = 0;          // of the last of them (when has_records)
  TailProblem problem = TailProblem::none;  // the first damage, at good_end
  std::uint64_t damaged_bytes = 0;          // damaged bytes in the whole file
  std::uint64_t later_records = 0;          // valid records after the first damage
  std::uint64_t first_later_offset = 0;     // where the first of them starts
  // Complete, CRC-valid records refused anywhere (unknown version or type, invalid
  // values, another journal, out of order): never cut.
  std::uint64_t refused_records = 0;
  std::uint64_t first_refused_offset = 0;
  TailProblem first_refused = TailProblem::none;
  JournalFormat format{};

  // The probe offset given to survey_journal(): it starts a record of the good prefix
  // or is its end (a checkpoint's anchor), with probe_records records before it.
  bool probe_is_boundary = false;
  std::uint64_t probe_records = 0;

  bool clean() const { return problem == TailProblem::none; }
  // Damage an append can leave with nothing valid or refused after it: an interrupted
  // append; cut [good_end, end).
  bool torn_tail() const { return problem != TailProblem::none && !corrupt(); }
  // Damage followed by valid records, or a refused record: never cut; refuse and
  // salvage instead.
  bool corrupt() const { return later_records > 0 || refused_records > 0; }
};

// Scans the whole file. data_loss: not a journal (or a damaged header); not_supported:
// a newer format version; io_error: storage failure.
// `probe`: an offset to check against the good prefix (see probe_is_boundary).
Result<JournalSurvey> survey_journal(ports::Storage& storage, std::uint64_t probe = 0);

}  // namespace twister::journal
