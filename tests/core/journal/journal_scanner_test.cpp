// JournalScanner, survey_journal() and salvage_journal() (issue 11, item 1): damage at
// every byte of every record is either a torn tail (nothing valid after it) or
// corruption (valid records after it, counted exactly), and salvage keeps every valid
// record that can still be replayed.
#include "twister/journal/journal_scanner.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_salvage.hpp"
#include "twister/journal/journal_writer.hpp"

namespace twister::journal {
namespace {

JournalRecord stroke(std::uint32_t sequence, std::uint16_t chain_step = 0) {
  JournalRecord r;
  r.sequence = sequence;
  r.stroke.hand_mask = 2;
  r.stroke.chain_step = chain_step;
  r.stroke.radius_m = 0.25;
  r.stroke.end[1].origin = {0.01 * sequence, 0, 0};
  return r;
}

// n records (sequences 0..n-1); offsets[i] = where record i starts; offsets[n] = end.
// A version 2 journal (what the writer makes), or version 1 (journals from before).
std::unique_ptr<test::FakeStorage> journal_of(const std::vector<JournalRecord>& records,
                                              std::vector<std::size_t>& offsets,
                                              std::uint32_t version = kNewestFileVersion) {
  auto storage = std::make_unique<test::FakeStorage>();
  if (version == kFileVersion1) {
    const auto header = file_header(kVersion1Format);
    storage->load(std::span<const std::byte>(header).first(kVersion1Format.header_bytes()));
  }
  JournalWriter writer(*storage);
  EXPECT_TRUE(writer.open().ok());
  for (const JournalRecord& r : records) {
    offsets.push_back(storage->bytes().size());
    EXPECT_TRUE(writer.append(r).ok());
  }
  offsets.push_back(storage->bytes().size());
  return storage;
}

TEST(JournalSurvey, ACleanJournalIsClean) {
  std::vector<std::size_t> at;
  auto s = journal_of({stroke(0), stroke(1), stroke(2)}, at);
  const auto v = survey_journal(*s);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->clean());
  EXPECT_EQ(v->records, 3u);
  EXPECT_EQ(v->good_end, at[3]);
  EXPECT_EQ(v->last_sequence, 2u);
}

TEST(JournalSurvey, AFlippedBitAnywhereInRecordKOfNCountsTheNMinusKLaterRecords) {
  constexpr std::uint32_t kN = 6;
  std::vector<JournalRecord> records;
  for (std::uint32_t i = 0; i < kN; ++i) records.push_back(stroke(i));
  std::vector<std::size_t> at;
  const auto original = journal_of(records, at);
  for (std::uint32_t k = 0; k < kN; ++k) {
    for (std::size_t byte = at[k]; byte < at[k + 1]; ++byte) {
      SCOPED_TRACE(byte);
      test::FakeStorage s;
      s.load(original->bytes());
      s.corrupt(byte, std::byte{0x10});
      const auto v = survey_journal(s);
      ASSERT_TRUE(v.ok());
      EXPECT_EQ(v->records, k);
      EXPECT_EQ(v->good_end, at[k]);
      EXPECT_EQ(v->later_records, kN - 1 - k);
      EXPECT_EQ(v->corrupt(), k + 1 < kN);
      EXPECT_EQ(v->torn_tail(), k + 1 == kN);
      if (k + 1 < kN) {
        EXPECT_EQ(v->first_later_offset, at[k + 1]);
      }
    }
  }
}

TEST(JournalSurvey, ATornAppendAtEveryByteIsATornTail) {
  std::vector<std::size_t> at;
  const auto full = journal_of({stroke(0), stroke(1)}, at);
  for (std::size_t cut = at[1] + 1; cut < at[2]; ++cut) {
    test::FakeStorage s;
    s.load(full->bytes().first(cut));
    const auto v = survey_journal(s);
    ASSERT_TRUE(v.ok());
    EXPECT_TRUE(v->torn_tail()) << cut;
    EXPECT_EQ(v->records, 1u);
    EXPECT_EQ(v->good_end, at[1]);
  }
  // Zeros where an append never landed (a file extended but not written) are torn too.
  test::FakeStorage zeros;
  zeros.load(full->bytes().first(at[1]));
  const std::array<std::byte, 300> nothing{};
  ASSERT_TRUE(zeros.append(nothing).ok());
  EXPECT_TRUE(survey_journal(zeros)->torn_tail());
}

TEST(JournalSurvey, AForeignFileIsNotAJournal) {
  test::FakeStorage s;
  const char text[] = "hello, not a journal";
  s.load(std::as_bytes(std::span(text)));
  EXPECT_EQ(survey_journal(s).status().code(), StatusCode::data_loss);
}

// Version 1 (as before issue 21): every valid record past the damage.
TEST(JournalSalvage, KeepsEveryValidRecordAndDropsFreezeStepsThatLostTheirChain) {
  // 0: stroke, 1: chain step 0, 2: step 1, 3: step 2, 4: stroke. Damage record 2.
  std::vector<std::size_t> at;
  const auto s = journal_of({stroke(0), stroke(1, 0), stroke(2, 1), stroke(3, 2), stroke(4)}, at,
                            kFileVersion1);
  s->corrupt(at[2] + 20, std::byte{0x01});
  test::FakeFileSink out;
  const auto report = salvage_journal(*s, out);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->records_found, 4u);
  EXPECT_EQ(report->damaged_ranges, 1u);
  EXPECT_EQ(report->damaged_bytes, at[3] - at[2]);
  EXPECT_EQ(report->broken_chain, 1u);  // step 2 without step 1
  EXPECT_EQ(report->records_kept, 3u);
  test::FakeStorage copy;
  copy.load(out.bytes());
  const auto v = survey_journal(copy);
  ASSERT_TRUE(v.ok());
  EXPECT_TRUE(v->clean());
  EXPECT_EQ(v->records, 3u);
  EXPECT_EQ(v->last_sequence, 4u);
  // Kept records are byte for byte the originals.
  EXPECT_TRUE(std::equal(out.bytes().begin() + static_cast<std::ptrdiff_t>(at[0]),
                         out.bytes().begin() + static_cast<std::ptrdiff_t>(at[2]),
                         s->bytes().begin() + static_cast<std::ptrdiff_t>(at[0])));
}

// Version 2: the longest ordered valid prefix; what follows the lost record is dropped
// and counted (issue 21).
TEST(JournalSalvage, Version2KeepsTheOrderedPrefixBeforeADamagedRecord) {
  std::vector<std::size_t> at;
  const auto s = journal_of({stroke(0), stroke(1, 0), stroke(2, 1), stroke(3, 2), stroke(4)}, at);
  s->corrupt(at[2] + 20, std::byte{0x01});
  test::FakeFileSink out;
  const auto report = salvage_journal(*s, out);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->records_found, 4u);
  EXPECT_EQ(report->damaged_ranges, 1u);
  EXPECT_EQ(report->after_gap, 2u);
  EXPECT_EQ(report->records_kept, 2u);
  ASSERT_EQ(out.bytes().size(), at[2]);
  EXPECT_TRUE(std::equal(out.bytes().begin(), out.bytes().end(), s->bytes().begin()));
}

TEST(JournalSalvage, AWriteFailureNamesNothing) {
  std::vector<std::size_t> at;
  const auto s = journal_of({stroke(0), stroke(1)}, at);
  test::FakeFileSink out;
  out.fail_writes_after(at[1] + 3);
  EXPECT_EQ(salvage_journal(*s, out).status().code(), StatusCode::io_error);
  EXPECT_EQ(out.commits(), 0u);
}

}  // namespace
}  // namespace twister::journal
