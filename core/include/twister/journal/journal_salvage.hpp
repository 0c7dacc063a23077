// salvage_journal(): a repaired copy of a damaged journal, in the input's format
// (same header, records copied byte for byte with their sequences) written through a
// FileSink (one sync at the end, atomically named).
//
// A version 2 journal (journal_format.hpp): the copy is the longest ordered valid
// prefix: the records of sequence 0, 1, 2, ... in file order, as long as each next one
// is found (past damaged ranges, duplicates, records out of order and records of
// another journal, which are dropped). When the next sequence is missing (lost in a
// damaged range, cut out, or dropped below), every record after it is dropped: they
// were sculpted on a model that had it, and a copy with a gap would be refused.
// A version 1 journal (no order to prove), as before: every valid record past any
// damaged range.
// In both, records that could no longer be replayed are dropped too: a freeze step
// whose chain lost a step (its weights come from the steps before it), and whatever
// the caller's RecordFilter refuses (`twister journal salvage --mesh` replays each
// record onto the model and drops those that do not apply). Everything skipped is
// reported to the SalvageObserver, so the tool can say what was lost. No allocation.
// Not thread-safe.
#pragma once

#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/journal/journal_scanner.hpp"
#include "twister/ports/file_sink.hpp"
#include "twister/ports/storage.hpp"

namespace twister::journal {

struct SalvageReport {
  std::uint64_t records_found = 0;   // valid records in the input
  std::uint64_t records_kept = 0;    // copied to the output
  std::uint64_t damaged_ranges = 0;  // damaged byte ranges skipped
  std::uint64_t damaged_bytes = 0;
  std::uint64_t broken_chain = 0;  // freeze steps dropped: an earlier step of theirs was lost
  std::uint64_t refused = 0;       // dropped by the RecordFilter
  std::uint64_t out_of_order = 0;  // version 2: duplicates and records of an earlier sequence
  std::uint64_t after_gap = 0;     // version 2: records after a missing sequence
};

class SalvageObserver {
 public:
  virtual ~SalvageObserver() = default;
  virtual void damaged(std::uint64_t /*offset*/, std::uint64_t /*bytes*/, TailProblem /*problem*/) {
  }
  enum class Drop : std::uint8_t { broken_chain, refused, out_of_order, after_gap };
  virtual void dropped(const ScanItem& /*record*/, Drop /*why*/) {}
};

// Decides about each record that survived the structural checks (in file order).
class RecordFilter {
 public:
  virtual ~RecordFilter() = default;
  virtual bool keep(const JournalRecord& record) = 0;
};

// Copies `in`'s valid records into a new file through `out` (begin ... commit).
// data_loss: `in` is not a journal; not_supported: a newer format; io_error: reading `in` or
// writing `out` failed
// (`out` aborted, nothing named); `out`'s own refusals (failed_precondition).
Result<SalvageReport> salvage_journal(ports::Storage& in, ports::FileSink& out,
                                      SalvageObserver* observer = nullptr,
                                      RecordFilter* filter = nullptr);

}  // namespace twister::journal
