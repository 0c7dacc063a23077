// Station start-up on journals that must prove their order (issue 21, items 2, 3, 7):
// a duplicated or spliced record before a checkpoint's anchor is refused, so the
// station's model can never differ from `twister replay` of the same journal; recover()
// changes no byte (the torn tail is cut and a new journal's header written only by
// begin_appending(), once the program's other start-up steps succeeded); a full disk
// under a new journal is an io_error that leaves no byte behind.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fakes/fake_button_source.hpp"
#include "fakes/fake_byte_stream.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/base/checksum.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/station/station.hpp"

namespace twister::station {
namespace {

using Mesh = mesh::MeshWithStorage<64, 128>;
using Work = session::SculptStorageArrays<64, 64, 256, 8>;
using Bytes = std::vector<std::byte>;

journal::JournalRecord move(std::uint32_t sequence) {
  journal::JournalRecord r;
  r.type = journal::RecordType::object_move;
  r.sequence = sequence;
  r.move.object_after.origin = {0.1 * sequence, 0, 0};
  return r;
}

struct Rig {
  Rig() {
    for (int i = 0; i < 16; ++i) (void)mesh.add_vertex({0.01f * static_cast<float>(i), 0, 0});
  }
  // n object moves, sequences 0..n-1, in a journal of identity `id`; record offsets.
  std::vector<std::size_t> write_moves(std::uint32_t n, std::uint32_t id = 7) {
    journal::JournalWriter writer(storage);
    writer.set_new_journal_id(id);
    EXPECT_TRUE(writer.open().ok());
    std::vector<std::size_t> at;
    for (std::uint32_t i = 0; i < n; ++i) {
      at.push_back(storage.bytes().size());
      EXPECT_TRUE(writer.append(move(i)).ok());
    }
    at.push_back(storage.bytes().size());
    return at;
  }
  Station& station(StationFiles files = {}) {
    core = std::make_unique<Station>(stream, buttons, clock, storage, mesh, work->spans(),
                                     StationConfig{}, files);
    return *core;
  }
  Bytes bytes() const { return {storage.bytes().begin(), storage.bytes().end()}; }

  test::FakeByteStream stream;
  test::FakeButtonSource buttons;
  test::FakeClock clock;
  test::FakeStorage storage;
  Mesh mesh;
  std::unique_ptr<Work> work = std::make_unique<Work>();
  std::unique_ptr<Station> core;
};

Bytes checkpoint_of(Rig& rig) {
  test::FakeFileSink out;
  EXPECT_TRUE(rig.station({nullptr, nullptr, &out}).start().ok());
  rig.core->stop();
  return {out.bytes().begin(), out.bytes().end()};
}

// Before issue 21 a same-length record copied over one before the checkpoint's anchor
// kept the anchor valid: the station restored the checkpoint (the old model) while
// `twister replay` replayed the edited journal. Now the scan refuses it, with or
// without the checkpoint, like `twister replay` does.
TEST(StationOrder, ARecordReplacedBeforeTheCheckpointAnchorIsRefusedWithItsOffset) {
  Rig rig;
  const auto at = rig.write_moves(6);
  const Bytes checkpoint = checkpoint_of(rig);
  const Bytes journal = rig.bytes();
  const std::size_t len = at[2] - at[1];
  struct Case {
    Bytes record;
    journal::TailProblem problem;
  };
  Rig other;  // the same sequence from another journal
  const auto other_at = other.write_moves(3, 99);
  const std::vector<Case> cases{
      {Bytes(journal.begin() + static_cast<std::ptrdiff_t>(at[1]),
             journal.begin() + static_cast<std::ptrdiff_t>(at[2])),
       journal::TailProblem::duplicate},
      {Bytes(other.storage.bytes().begin() + static_cast<std::ptrdiff_t>(other_at[2]),
             other.storage.bytes().begin() + static_cast<std::ptrdiff_t>(other_at[3])),
       journal::TailProblem::other_journal}};
  for (const Case& c : cases) {
    ASSERT_EQ(c.record.size(), len);
    Rig edited;
    Bytes file = journal;
    std::copy(c.record.begin(), c.record.end(), file.begin() + static_cast<std::ptrdiff_t>(at[2]));
    edited.storage.load(file);
    test::FakeStorage in;
    in.load(checkpoint);
    EXPECT_EQ(edited.station({nullptr, &in, nullptr}).start().code(), StatusCode::data_loss);
    const JournalRecovery& r = edited.core->recovery();
    EXPECT_EQ(r.outcome, JournalRecovery::Outcome::corrupt);
    EXPECT_EQ(r.survey.first_refused, c.problem);
    EXPECT_EQ(r.survey.first_refused_offset, at[2]);
    EXPECT_EQ(edited.bytes(), file);
  }
}

TEST(StationOrder, AnUndecodableLastRecordIsRefusedNotCut) {
  Rig rig;
  const auto at = rig.write_moves(3);
  Bytes file = rig.bytes();
  file[at[2] + 4] = std::byte{9};  // a record version from a newer station
  const std::size_t body = file.size() - journal::kRecordCrcBytes;
  const std::uint32_t crc = crc32(std::span<const std::byte>(file).subspan(at[2], body - at[2]));
  for (std::size_t i = 0; i < 4; ++i)
    file[body + i] = static_cast<std::byte>((crc >> (8 * i)) & 0xffu);
  Rig edited;
  edited.storage.load(file);
  test::FakeFileSink archive;
  EXPECT_EQ(edited.station({&archive}).start().code(), StatusCode::data_loss);
  EXPECT_EQ(edited.core->recovery().outcome, JournalRecovery::Outcome::corrupt);
  EXPECT_EQ(edited.core->recovery().survey.first_refused, journal::TailProblem::unknown_version);
  EXPECT_EQ(edited.core->recovery().survey.first_refused_offset, at[2]);
  EXPECT_EQ(edited.bytes(), file);
  EXPECT_EQ(archive.commits(), 0u);
}

TEST(StationOrder, RecoverChangesNoByteBeginAppendingCutsTheTornTail) {
  Rig rig;
  const auto at = rig.write_moves(3);
  const std::array<std::byte, 9> torn{std::byte{92}, std::byte{0}, std::byte{0}, std::byte{0},
                                      std::byte{1},  std::byte{2}, std::byte{0}, std::byte{0}};
  ASSERT_TRUE(rig.storage.append(torn).ok());
  const Bytes before = rig.bytes();
  test::FakeFileSink archive;
  Station& s = rig.station({&archive});
  ASSERT_TRUE(s.recover().ok());
  // A later start-up step fails here (the display link): nothing was written.
  EXPECT_EQ(rig.bytes(), before);
  EXPECT_EQ(archive.commits(), 0u);
  EXPECT_EQ(s.poll().code(), StatusCode::failed_precondition);
  ASSERT_TRUE(s.begin_appending().ok());
  EXPECT_EQ(rig.storage.bytes().size(), at[3]);
  EXPECT_EQ(archive.commits(), 1u);
  EXPECT_EQ(s.begin_appending().code(), StatusCode::failed_precondition);
}

TEST(StationOrder, ANewJournalGetsItsIdentityOnlyWhenAppendingBegins) {
  Rig rig;
  StationFiles files;
  files.new_journal_id = 0xfeedbeef;
  Station& s = rig.station(files);
  ASSERT_TRUE(s.recover().ok());
  EXPECT_TRUE(rig.storage.bytes().empty());
  ASSERT_TRUE(s.begin_appending().ok());
  journal::JournalFormat format{};
  ASSERT_EQ(journal::check_file_header(rig.storage.bytes(), format), journal::HeaderCheck::ok);
  EXPECT_EQ(format, journal::version2_format(0xfeedbeef));
}

TEST(StationOrder, ANewJournalOnAFullDiskIsAnIoErrorThatLeavesNoByte) {
  Rig rig;
  rig.storage.fill_disk_at(5);
  EXPECT_EQ(rig.station().start().code(), StatusCode::io_error);
  EXPECT_EQ(rig.core->recovery().outcome, JournalRecovery::Outcome::io_error);
  EXPECT_TRUE(rig.storage.bytes().empty());
}

}  // namespace
}  // namespace twister::station
