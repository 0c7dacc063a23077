#include "twister/journal/journal_reader.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_writer.hpp"

namespace twister::journal {
namespace {

JournalRecord stroke(std::uint32_t seq) {
  JournalRecord r;
  r.type = RecordType::stroke;
  r.sequence = seq;
  r.stroke.hand_mask = 1;
  r.stroke.radius_m = 0.5;
  r.stroke.end[0].origin = {0.01 * seq, 0.0, 0.0};
  return r;
}

std::vector<JournalRecord> read_all(JournalReader& reader, Status* end) {
  std::vector<JournalRecord> out;
  EXPECT_TRUE(reader.open().ok());
  for (;;) {
    auto r = reader.next();
    if (!r.ok()) {
      *end = r.status();
      return out;
    }
    out.push_back(*r);
  }
}

TEST(JournalReader, EmptyFileIsAnEmptyJournal) {
  test::FakeStorage storage;
  JournalReader reader(storage);
  Status end;
  EXPECT_TRUE(read_all(reader, &end).empty());
  EXPECT_EQ(end.code(), StatusCode::unavailable);
}

TEST(JournalReader, ReadsBackWhatTheWriterAppendedAndSynced) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  ASSERT_TRUE(writer.open().ok());
  for (std::uint32_t i = 0; i < 5; ++i) ASSERT_TRUE(writer.append(stroke(i)).ok());
  EXPECT_EQ(storage.sync_count(), 6u);  // header + one per record
  EXPECT_EQ(storage.synced_size(), storage.bytes().size());
  JournalReader reader(storage);
  Status end;
  const auto records = read_all(reader, &end);
  EXPECT_EQ(end.code(), StatusCode::unavailable);
  ASSERT_EQ(records.size(), 5u);
  for (std::uint32_t i = 0; i < 5; ++i) EXPECT_EQ(records[i], stroke(i));
}

// Power cut at every byte of an append: the reader returns exactly the records
// before it, reports the tail, and after truncation the file takes new records.
TEST(JournalReader, TornAppendAtEveryByteIsDetectedAndTruncated) {
  test::FakeStorage reference;
  JournalWriter ref_writer(reference);
  ASSERT_TRUE(ref_writer.open().ok());
  for (std::uint32_t i = 0; i < 3; ++i) ASSERT_TRUE(ref_writer.append(stroke(i)).ok());
  const std::size_t before = reference.bytes().size();
  ASSERT_TRUE(ref_writer.append(stroke(3)).ok());
  const std::size_t record_bytes = reference.bytes().size() - before;

  for (std::size_t cut = 0; cut < record_bytes; ++cut) {
    SCOPED_TRACE(cut);
    test::FakeStorage storage;
    JournalWriter writer(storage);
    ASSERT_TRUE(writer.open().ok());
    for (std::uint32_t i = 0; i < 3; ++i) ASSERT_TRUE(writer.append(stroke(i)).ok());
    storage.cut_power_after(cut);
    EXPECT_EQ(writer.append(stroke(3)).code(), StatusCode::io_error);
    storage.power_on();  // reboot

    JournalReader reader(storage);
    Status end;
    const auto records = read_all(reader, &end);
    ASSERT_EQ(records.size(), 3u);
    if (cut == 0) {
      EXPECT_EQ(end.code(), StatusCode::unavailable);
    } else {
      EXPECT_EQ(end.code(), StatusCode::data_loss);
      EXPECT_EQ(reader.tail_bytes(), cut);
      EXPECT_TRUE(reader.problem() == TailProblem::torn_header ||
                  reader.problem() == TailProblem::torn_record);
    }
    ASSERT_TRUE(reader.truncate_tail().ok());
    EXPECT_EQ(storage.bytes().size(), before);
    JournalWriter again(storage);
    ASSERT_TRUE(again.open().ok());
    ASSERT_TRUE(again.append(stroke(3)).ok());
    EXPECT_EQ(std::vector<std::byte>(storage.bytes().begin(), storage.bytes().end()),
              std::vector<std::byte>(reference.bytes().begin(), reference.bytes().end()));
  }
}

TEST(JournalReader, TornFileHeaderIsCutToEmpty) {
  for (std::size_t cut = 1; cut < kMaxFileHeaderBytes; ++cut) {
    test::FakeStorage storage;
    storage.cut_power_after(cut);
    JournalWriter writer(storage);
    EXPECT_FALSE(writer.open().ok());
    storage.power_on();
    JournalReader reader(storage);
    ASSERT_TRUE(reader.open().ok());
    EXPECT_EQ(reader.next().status().code(), StatusCode::data_loss);
    EXPECT_EQ(reader.problem(), TailProblem::torn_header);
    ASSERT_TRUE(reader.truncate_tail().ok());
    EXPECT_TRUE(storage.bytes().empty());
  }
}

TEST(JournalReader, CorruptByteStopsReadingThere) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  ASSERT_TRUE(writer.open().ok());
  ASSERT_TRUE(writer.append(stroke(0)).ok());
  const std::size_t first_end = storage.bytes().size();
  ASSERT_TRUE(writer.append(stroke(1)).ok());
  ASSERT_TRUE(writer.append(stroke(2)).ok());
  storage.corrupt(first_end + 20, std::byte{0x04});  // inside record 1's payload
  JournalReader reader(storage);
  Status end;
  const auto records = read_all(reader, &end);
  ASSERT_EQ(records.size(), 1u);  // record 2 is behind the corrupt one: not applied
  EXPECT_EQ(end.code(), StatusCode::data_loss);
  EXPECT_EQ(reader.problem(), TailProblem::bad_crc);
  EXPECT_EQ(reader.good_end(), first_end);
}

TEST(JournalReader, HugeLengthIsCorruptNotAnAllocation) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  ASSERT_TRUE(writer.open().ok());
  ASSERT_TRUE(writer.append(stroke(0)).ok());
  storage.corrupt(kMaxFileHeaderBytes + 3, std::byte{0x80});
  JournalReader reader(storage);
  ASSERT_TRUE(reader.open().ok());
  EXPECT_EQ(reader.next().status().code(), StatusCode::data_loss);
  EXPECT_EQ(reader.problem(), TailProblem::bad_length);
}

TEST(JournalReader, ForeignFileIsRefusedAndLeftAlone) {
  test::FakeStorage storage;
  const char text[] = "hello world, not a journal";
  storage.load(std::as_bytes(std::span(text)));
  JournalReader reader(storage);
  EXPECT_EQ(reader.open().code(), StatusCode::data_loss);
  JournalWriter writer(storage);
  EXPECT_EQ(writer.open().code(), StatusCode::data_loss);
  EXPECT_EQ(storage.bytes().size(), sizeof(text));
}

TEST(JournalWriter, FailedSyncCutsTheRecordOff) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  ASSERT_TRUE(writer.open().ok());
  ASSERT_TRUE(writer.append(stroke(0)).ok());
  const std::size_t good = storage.bytes().size();
  storage.fail_next_sync();
  EXPECT_EQ(writer.append(stroke(1)).code(), StatusCode::io_error);
  EXPECT_EQ(storage.bytes().size(), good);
  EXPECT_TRUE(writer.healthy());
  ASSERT_TRUE(writer.append(stroke(2)).ok());
}

TEST(JournalWriter, RefusesAppendsAfterAnUnrecoverableFailure) {
  test::FakeStorage storage;
  JournalWriter writer(storage);
  ASSERT_TRUE(writer.open().ok());
  storage.cut_power_after(5);
  EXPECT_EQ(writer.append(stroke(0)).code(), StatusCode::io_error);
  EXPECT_FALSE(writer.healthy());
  storage.power_on();
  EXPECT_EQ(writer.append(stroke(1)).code(), StatusCode::failed_precondition);
}

}  // namespace
}  // namespace twister::journal
