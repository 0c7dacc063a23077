// salvage_journal(): a repaired copy of a damaged journal. Every valid record of the
// input (found by JournalScanner, past any damaged range) is copied byte for byte, in
// file order and with its sequence, into a new journal written through a FileSink
// (one sync at the end, atomically named), except records that could no longer be
// replayed: a freeze step whose chain lost a step (its weights come from the steps
// before it), and whatever the caller's RecordFilter refuses (`twister journal
// salvage --mesh` replays each record onto the model and drops those that do not
// apply). Everything skipped is reported to the SalvageObserver, so the tool can say
// what was lost. No allocation. Not thread-safe.
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
};

class SalvageObserver {
 public:
  virtual ~SalvageObserver() = default;
  virtual void damaged(std::uint64_t /*offset*/, std::uint64_t /*bytes*/, TailProblem /*problem*/) {
  }
  enum class Drop : std::uint8_t { broken_chain, refused };
  virtual void dropped(const ScanItem& /*record*/, Drop /*why*/) {}
};

// Decides about each record that survived the structural checks (in file order).
class RecordFilter {
 public:
  virtual ~RecordFilter() = default;
  virtual bool keep(const JournalRecord& record) = 0;
};

// Copies `in`'s valid records into a new file through `out` (begin ... commit).
// data_loss: `in` is not a journal; io_error: reading `in` or writing `out` failed
// (`out` aborted, nothing named); `out`'s own refusals (failed_precondition).
Result<SalvageReport> salvage_journal(ports::Storage& in, ports::FileSink& out,
                                      SalvageObserver* observer = nullptr,
                                      RecordFilter* filter = nullptr);

}  // namespace twister::journal
