// Fuzz target of the journal scanner, survey_journal() and salvage_journal() (issue 11).
// Input: a journal file. Properties: never crashes or reads out of bounds; the
// scanner's records and damaged ranges tile the file exactly; the survey agrees with
// JournalReader on the good prefix (records, end, first problem) and calls it torn or
// corrupt consistently; the salvaged copy scans clean and holds exactly the kept
// records, byte for byte, in order.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_salvage.hpp"
#include "twister/journal/journal_scanner.hpp"

namespace {

using namespace twister;

constexpr std::size_t kMaxInput = 1 << 14;
using Storage = test::FakeStorageWithStorage<kMaxInput + journal::kFileHeaderBytes>;
using Sink = test::FakeFileSinkWithStorage<kMaxInput + journal::kFileHeaderBytes>;

void check(bool ok) {
  if (!ok) std::abort();
}

// Records and damage cover [header, size) with no gap or overlap.
void check_tiling(Storage& storage, std::size_t size) {
  journal::JournalScanner scanner(storage);
  if (!scanner.open().ok()) return;
  std::uint64_t at = size >= journal::kFileHeaderBytes ? journal::kFileHeaderBytes : 0;
  for (auto item = scanner.next(); item.ok(); item = scanner.next()) {
    check(item->offset == at && item->bytes > 0);
    at += item->bytes;
  }
  check(at == size);
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
  for (auto item = scanner.next(); item.ok(); item = scanner.next()) {
    check(item->kind == journal::ScanItem::Kind::record);
    ++kept;
  }
  check(kept == report->records_kept);
  check(report->records_kept + report->broken_chain == report->records_found);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return 0;
  static Storage storage;
  storage = Storage();
  storage.load(std::as_bytes(std::span(data, size)));
  auto survey = journal::survey_journal(storage);
  if (!survey.ok()) {
    check(survey.status().code() == StatusCode::data_loss);  // not a journal
    return 0;
  }
  check_tiling(storage, size);
  check_survey(storage, *survey);
  check_salvage(storage);
  return 0;
}
