// Journal format version 2 (issue 21, items 2 and 3): a journal proves its own order.
// Duplicated, spliced (another journal's), out-of-order and missing records, and
// complete CRC-valid records this program cannot decode (a newer record version, an
// unknown type, a NaN pose), are refused with their offsets wherever they are, never
// cut as a torn tail; salvage keeps the longest ordered valid prefix and says what it
// dropped. Version 1 journals read exactly as before.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/base/checksum.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_salvage.hpp"
#include "twister/journal/journal_scanner.hpp"
#include "twister/journal/journal_writer.hpp"

namespace twister::journal {
namespace {

using Bytes = std::vector<std::byte>;

JournalRecord stroke(std::uint32_t sequence) {
  JournalRecord r;
  r.sequence = sequence;
  r.stroke.hand_mask = 1;
  r.stroke.radius_m = 0.25;
  r.stroke.end[0].origin = {0.01 * sequence, 0, 0};
  return r;
}

Bytes record_bytes(const JournalRecord& r, const JournalFormat& format) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(r, buf, format);
  EXPECT_TRUE(n.ok());
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n));
}

// A journal file of `format` holding `records` (each a whole encoded record).
Bytes file_of(const JournalFormat& format, const std::vector<Bytes>& records) {
  const auto header = file_header(format);
  Bytes out(header.begin(), header.begin() + static_cast<std::ptrdiff_t>(format.header_bytes()));
  for (const Bytes& r : records) out.insert(out.end(), r.begin(), r.end());
  return out;
}

std::vector<Bytes> strokes(std::uint32_t n, const JournalFormat& format) {
  std::vector<Bytes> out;
  for (std::uint32_t i = 0; i < n; ++i) out.push_back(record_bytes(stroke(i), format));
  return out;
}

// Offset of record k in file_of(format, records).
std::size_t offset_of(const JournalFormat& format, const std::vector<Bytes>& records,
                      std::size_t k) {
  std::size_t at = format.header_bytes();
  for (std::size_t i = 0; i < k; ++i) at += records[i].size();
  return at;
}

// Makes the record's CRC right again after an edit.
void reseal(Bytes& record) {
  const std::size_t body = record.size() - kRecordCrcBytes;
  const std::uint32_t crc = crc32(std::span<const std::byte>(record).first(body));
  for (std::size_t i = 0; i < 4; ++i)
    record[body + i] = static_cast<std::byte>((crc >> (8 * i)) & 0xffu);
}

std::unique_ptr<test::FakeStorage> storage_of(const Bytes& bytes) {
  auto s = std::make_unique<test::FakeStorage>();
  s->load(bytes);
  return s;
}

struct Refusal {
  std::uint64_t offset;
  TailProblem problem;
};

// The survey must call it corruption (never a torn tail) with the refusal first.
void expect_refused(const Bytes& file, Refusal want) {
  const auto s = storage_of(file);
  const auto v = survey_journal(*s);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->corrupt());
  EXPECT_FALSE(v->torn_tail());
  EXPECT_EQ(v->first_refused_offset, want.offset);
  EXPECT_EQ(v->first_refused, want.problem);
  EXPECT_EQ(v->good_end, want.offset);
  // The reader stops there with the same problem and refuses to cut it.
  JournalReader reader(*s);
  ASSERT_TRUE(reader.open().ok());
  for (auto r = reader.next(); r.ok(); r = reader.next()) {
  }
  EXPECT_EQ(reader.problem(), want.problem);
  EXPECT_EQ(reader.good_end(), want.offset);
  EXPECT_EQ(reader.truncate_tail().code(), StatusCode::data_loss);
  EXPECT_EQ(Bytes(s->bytes().begin(), s->bytes().end()), file);  // nothing cut
}

struct Salvaged {
  SalvageReport report;
  Bytes copy;
};

Salvaged salvage(const Bytes& file) {
  const auto s = storage_of(file);
  test::FakeFileSink out;
  const auto report = salvage_journal(*s, out);
  EXPECT_TRUE(report.ok());
  Salvaged result{report.value_or(SalvageReport{}), Bytes(out.bytes().begin(), out.bytes().end())};
  // The copy is a clean journal.
  const auto copy = storage_of(result.copy);
  const auto v = survey_journal(*copy);
  EXPECT_TRUE(v.ok() && v->clean());
  return result;
}

const JournalFormat kV2 = version2_format(0x1234abcd);

TEST(JournalOrder, NewJournalsAreVersion2AndEveryRecordCarriesTheirIdentity) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  writer.set_new_journal_id(0x1234abcd);
  ASSERT_TRUE(writer.open().ok());
  EXPECT_EQ(writer.format(), kV2);
  for (std::uint32_t i = 0; i < 3; ++i) ASSERT_TRUE(writer.append(stroke(i)).ok());
  EXPECT_EQ(Bytes(storage.bytes().begin(), storage.bytes().end()), file_of(kV2, strokes(3, kV2)));
  JournalFormat read{};
  EXPECT_EQ(check_file_header(storage.bytes(), read), HeaderCheck::ok);
  EXPECT_EQ(read, kV2);
}

TEST(JournalOrder, ADuplicatedRecordIsRefusedWithItsOffsetEvenAsTheLastRecord) {
  for (std::size_t k : {1u, 4u}) {  // in the middle, and the last record duplicated
    SCOPED_TRACE(k);
    auto records = strokes(5, kV2);
    records.insert(records.begin() + static_cast<std::ptrdiff_t>(k + 1), records[k]);
    const Bytes file = file_of(kV2, records);
    expect_refused(file, {offset_of(kV2, records, k + 1), TailProblem::duplicate});
    const Salvaged s = salvage(file);
    EXPECT_EQ(s.report.records_kept, 5u);
    EXPECT_EQ(s.report.out_of_order, 1u);
    EXPECT_EQ(s.copy, file_of(kV2, strokes(5, kV2)));
  }
}

TEST(JournalOrder, ARecordOfAnotherJournalIsRefusedWithItsOffsetEvenAsTheLastRecord) {
  const JournalFormat other = version2_format(0x0badf00d);
  for (std::size_t k : {2u, 5u}) {
    SCOPED_TRACE(k);
    auto records = strokes(5, kV2);
    // The other journal's record of the sequence due here: only the identity tells.
    records.insert(records.begin() + static_cast<std::ptrdiff_t>(k),
                   record_bytes(stroke(static_cast<std::uint32_t>(k)), other));
    const Bytes file = file_of(kV2, records);
    expect_refused(file, {offset_of(kV2, records, k), TailProblem::other_journal});
    const Salvaged s = salvage(file);
    EXPECT_EQ(s.report.records_kept, 5u);
    EXPECT_EQ(s.copy, file_of(kV2, strokes(5, kV2)));
  }
}

TEST(JournalOrder, AGapIsRefusedAndSalvageKeepsTheOrderedPrefix) {
  auto records = strokes(6, kV2);
  records.erase(records.begin() + 3);  // sequence 3 cut out
  const Bytes file = file_of(kV2, records);
  expect_refused(file, {offset_of(kV2, records, 3), TailProblem::sequence_gap});
  const Salvaged s = salvage(file);
  EXPECT_EQ(s.report.records_kept, 3u);
  EXPECT_EQ(s.report.after_gap, 2u);  // 4 and 5 were made on a model that had 3
  EXPECT_EQ(s.copy, file_of(kV2, strokes(3, kV2)));
  // A journal whose first record is missing starts with a gap.
  auto late = strokes(3, kV2);
  late.erase(late.begin());
  expect_refused(file_of(kV2, late), {kV2.header_bytes(), TailProblem::sequence_gap});
}

TEST(JournalOrder, RecordsOutOfOrderAreRefusedAndSalvageKeepsTheLongestOrderedPrefix) {
  auto records = strokes(6, kV2);
  std::swap(records[2], records[3]);  // 0 1 3 2 4 5
  const Bytes file = file_of(kV2, records);
  expect_refused(file, {offset_of(kV2, records, 2), TailProblem::sequence_gap});
  const Salvaged s = salvage(file);
  EXPECT_EQ(s.report.records_kept, 3u);  // 0 1 2: 3 came too early, so 4 and 5 follow a gap
  EXPECT_EQ(s.copy, file_of(kV2, {records[0], records[1], records[3]}));
  // A copy of a later record spliced early: dropped, and the rest is kept.
  auto early = strokes(6, kV2);
  early.insert(early.begin() + 2, early[4]);  // 0 1 4 2 3 4 5
  const Bytes spliced = file_of(kV2, early);
  expect_refused(spliced, {offset_of(kV2, early, 2), TailProblem::sequence_gap});
  const Salvaged t = salvage(spliced);
  EXPECT_EQ(t.report.records_kept, 6u);
  EXPECT_EQ(t.copy, file_of(kV2, strokes(6, kV2)));
}

// A complete, CRC-valid record that does not decode, as the last record of a version 1
// and of a version 2 journal: refused with what it is, never cut.
TEST(JournalOrder, UndecodableCompleteRecordsAreRefusedNotCutAsATornTail) {
  for (const JournalFormat& format : {kVersion1Format, kV2}) {
    SCOPED_TRACE(format.version);
    const auto records = strokes(3, format);
    const std::size_t last = offset_of(format, records, 2);
    auto edit = [&](auto change) {
      auto edited = records;
      change(edited[2]);
      reseal(edited[2]);
      return file_of(format, edited);
    };
    expect_refused(edit([](Bytes& r) { r[4] = std::byte{9}; }),
                   {last, TailProblem::unknown_version});
    expect_refused(edit([](Bytes& r) { r[5] = std::byte{42}; }), {last, TailProblem::unknown_type});
    // A NaN in the end pose (the first f64 after the fixed stroke fields and the start pose).
    const std::size_t pose = format.record_header_bytes() + 4 + 4 + 8 + 72;
    expect_refused(edit([&](Bytes& r) {
                     const auto nan =
                         std::bit_cast<std::uint64_t>(std::numeric_limits<double>::quiet_NaN());
                     for (std::size_t i = 0; i < 8; ++i)
                       r[pose + i] = static_cast<std::byte>((nan >> (8 * i)) & 0xffu);
                   }),
                   {last, TailProblem::bad_payload});
  }
}

TEST(JournalOrder, Version1JournalsReadExactlyAsBefore) {
  // Version 1 proves no order: a duplicate is a valid record, as it always was, and
  // the writer appends version 1 records to a version 1 journal.
  auto records = strokes(3, kVersion1Format);
  records.push_back(records[2]);
  const auto s = storage_of(file_of(kVersion1Format, records));
  const auto v = survey_journal(*s);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->clean());
  EXPECT_EQ(v->records, 4u);
  JournalWriter writer(*s);
  ASSERT_TRUE(writer.open().ok());
  EXPECT_EQ(writer.format(), kVersion1Format);
  ASSERT_TRUE(writer.append(stroke(3)).ok());
  records.push_back(record_bytes(stroke(3), kVersion1Format));
  EXPECT_EQ(Bytes(s->bytes().begin(), s->bytes().end()), file_of(kVersion1Format, records));
  // Salvage of a version 1 journal keeps every valid record (no order to prove).
  EXPECT_EQ(salvage(file_of(kVersion1Format, records)).report.records_kept, 5u);
}

TEST(JournalOrder, DamagedOrNewerHeadersAreRefusedAndLeftAlone) {
  Bytes damaged = file_of(kV2, strokes(2, kV2));
  damaged[9] ^= std::byte{0x01};  // the identity
  Bytes newer = file_of(kV2, strokes(2, kV2));
  newer[4] = std::byte{3};
  for (const auto& [file, code] :
       {std::pair{damaged, StatusCode::data_loss}, std::pair{newer, StatusCode::not_supported}}) {
    const auto s = storage_of(file);
    JournalReader reader(*s);
    EXPECT_EQ(reader.open().code(), code);
    EXPECT_EQ(survey_journal(*s).status().code(), code);
    JournalWriter writer(*s);
    EXPECT_EQ(writer.open().code(), code);
    EXPECT_EQ(Bytes(s->bytes().begin(), s->bytes().end()), file);
  }
}

TEST(JournalOrder, AFullDiskLeavesNoTornHeaderBehindANewJournal) {
  test::FakeStorage storage;
  storage.fill_disk_at(10);
  JournalWriter writer(storage);
  EXPECT_EQ(writer.open().code(), StatusCode::io_error);
  EXPECT_TRUE(storage.bytes().empty());
}

}  // namespace
}  // namespace twister::journal
