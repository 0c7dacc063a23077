// Fuzz target of the journal scanner, survey_journal() and salvage_journal() (issues 11
// and 21). Input: a journal file (format version 1 or 2). Properties: never crashes or
// reads out of bounds; the scanner's records and damaged ranges tile the file exactly;
// the survey agrees with JournalReader on the good prefix (records, end, first problem)
// and calls it torn or corrupt consistently; a complete record that is refused
// (version, type, values, identity, order) is never part of a torn tail; cutting a torn
// tail leaves a clean journal of the same records; the salvaged copy scans clean, holds
// exactly the kept records, and in version 2 their sequences are 0, 1, 2, ...
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_salvage.hpp"
#include "twister/journal/journal_scanner.hpp"

namespace {

using namespace twister;

constexpr std::size_t kMaxInput = 1 << 14;
using Storage = test::FakeStorageWithStorage<kMaxInput + journal::kMaxFileHeaderBytes>;
using Sink = test::FakeFileSinkWithStorage<kMaxInput + journal::kMaxFileHeaderBytes>;

void check(bool ok) {
  if (!ok) std::abort();
}

// Records and damage cover [header, size) with no gap or overlap.
void check_tiling(Storage& storage, std::size_t size) {
  journal::JournalScanner scanner(storage);
  if (!scanner.open().ok()) return;
  std::uint64_t at = scanner.header() == journal::HeaderCheck::ok && size > 0
                         ? scanner.format().header_bytes()
                         : 0;
  bool refused = false;
  for (auto item = scanner.next(); item.ok(); item = scanner.next()) {
    check(item->offset == at && item->bytes > 0);
    at += item->bytes;
    if (item->kind == journal::ScanItem::Kind::damage && !journal::may_be_torn(item->problem)) {
      refused = true;
    }
  }
  check(at == size);
  const auto survey = journal::survey_journal(storage);
  check(survey.ok());
  if (refused) check(survey->corrupt() && !survey->torn_tail());
}

// The survey's good prefix is exactly what the reader returns.
void check_survey(Storage& storage, const journal::JournalSurvey& s) {
  journal::JournalReader reader(storage);
  check(reader.open().ok());
  std::uint64_t n = 0;
  for (auto r = reader.next(); r.ok(); r = reader.next()) ++n;
  check(n == s.records);
  check(reader.problem() == s.problem);
  check(s.file_size == 0 || reader.good_end() == s.good_end);
  check(!(s.torn_tail() && s.corrupt()));
  check(s.clean() == (s.damaged_bytes == 0));
  check(s.corrupt() == (s.later_records > 0 || s.refused_records > 0));
  // What the station does with a torn tail: cut it; the rest is clean, the same records.
  if (s.torn_tail()) {
    check(journal::may_be_torn(s.problem));
    static Storage cut;
    cut = Storage();
    cut.load(storage.bytes().first(static_cast<std::size_t>(s.good_end)));
    const auto again = journal::survey_journal(cut);
    check(!again.ok() || (again->clean() && again->records == s.records));
  }
}

void check_salvage(Storage& storage) {
  static Sink sink;
  sink = Sink();
  const auto report = journal::salvage_journal(storage, sink);
  check(report.ok());
  static Storage copy;
  copy = Storage();
  copy.load(sink.bytes());
  journal::JournalScanner scanner(copy);
  check(scanner.open().ok());
  std::uint64_t kept = 0;
  const bool ordered = scanner.format().proves_order();
  for (auto item = scanner.next(); item.ok(); item = scanner.next()) {
    check(item->kind == journal::ScanItem::Kind::record);
    if (ordered) check(item->record.sequence == kept);  // the ordered prefix
    ++kept;
  }
  check(kept == report->records_kept);
  check(report->records_kept + report->broken_chain + report->refused + report->out_of_order +
            report->after_gap ==
        report->records_found);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return 0;
  static Storage storage;
  storage = Storage();
  storage.load(std::as_bytes(std::span(data, size)));
  auto survey = journal::survey_journal(storage);
  if (!survey.ok()) {
    // Not a journal (or a damaged version 2 header), or a newer format: left alone.
    check(survey.status().code() == StatusCode::data_loss ||
          survey.status().code() == StatusCode::not_supported);
    return 0;
  }
  check_tiling(storage, size);
  check_survey(storage, *survey);
  check_salvage(storage);
  return 0;
}
