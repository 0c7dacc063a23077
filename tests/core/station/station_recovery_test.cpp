// Station::start() on damaged journals (issue 11, item 1): corruption is refused with
// the file byte-identical, a torn tail is copied to the tail archive before it is cut,
// and when the copy cannot be made nothing is cut.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fakes/fake_button_source.hpp"
#include "fakes/fake_byte_stream.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/station/station.hpp"

namespace twister::station {
namespace {

using Mesh = mesh::MeshWithStorage<64, 128>;
using Work = session::SculptStorageArrays<64, 64, 256, 8>;

struct Rig {
  Rig() {
    for (int i = 0; i < 16; ++i) (void)mesh.add_vertex({0.01f * static_cast<float>(i), 0, 0});
  }
  // n object moves (they apply to any model), sequences 0..n-1; returns record offsets.
  std::vector<std::size_t> write_moves(std::uint32_t n) {
    journal::JournalWriter writer(storage);
    EXPECT_TRUE(writer.open().ok());
    std::vector<std::size_t> at;
    for (std::uint32_t i = 0; i < n; ++i) {
      at.push_back(storage.bytes().size());
      journal::JournalRecord r;
      r.type = journal::RecordType::object_move;
      r.sequence = i;
      r.move.object_after.origin = {0.1 * i, 0, 0};
      EXPECT_TRUE(writer.append(r).ok());
    }
    at.push_back(storage.bytes().size());
    return at;
  }
  Station& station(StationFiles files = {}) {
    core = std::make_unique<Station>(stream, buttons, clock, storage, mesh, work->spans(),
                                     StationConfig{}, files);
    return *core;
  }

  test::FakeByteStream stream;
  test::FakeButtonSource buttons;
  test::FakeClock clock;
  test::FakeStorage storage;
  Mesh mesh;
  std::unique_ptr<Work> work = std::make_unique<Work>();
  std::unique_ptr<Station> core;
};

TEST(StationRecovery, CorruptionIsRefusedAndTheFileStaysByteIdentical) {
  Rig rig;
  const auto at = rig.write_moves(20);
  rig.storage.corrupt(at[4] + 30, std::byte{0x02});  // record 5 of 20
  const std::vector<std::byte> before(rig.storage.bytes().begin(), rig.storage.bytes().end());
  test::FakeFileSink archive;
  EXPECT_EQ(rig.station({&archive}).start().code(), StatusCode::data_loss);
  const JournalRecovery& r = rig.core->recovery();
  EXPECT_EQ(r.outcome, JournalRecovery::Outcome::corrupt);
  EXPECT_EQ(r.survey.good_end, at[4]);
  EXPECT_EQ(r.survey.later_records, 15u);
  EXPECT_EQ(r.survey.problem, journal::TailProblem::bad_crc);
  EXPECT_TRUE(std::equal(before.begin(), before.end(), rig.storage.bytes().begin(),
                         rig.storage.bytes().end()));
  EXPECT_EQ(archive.commits(), 0u);
  EXPECT_EQ(rig.core->poll().code(), StatusCode::failed_precondition);
}

TEST(StationRecovery, ATornTailIsKeptThenCut) {
  Rig rig;
  const auto at = rig.write_moves(3);
  const std::array<std::byte, 9> torn{std::byte{92}, std::byte{0}, std::byte{0},
                                      std::byte{0},  std::byte{1}, std::byte{2},
                                      std::byte{0},  std::byte{0}, std::byte{7}};
  ASSERT_TRUE(rig.storage.append(torn).ok());
  test::FakeFileSink archive;
  ASSERT_TRUE(rig.station({&archive}).start().ok());
  EXPECT_EQ(rig.core->recovery().tail_cut, torn.size());
  EXPECT_TRUE(rig.core->recovery().tail_kept);
  ASSERT_EQ(archive.bytes().size(), torn.size());
  EXPECT_TRUE(std::equal(torn.begin(), torn.end(), archive.bytes().begin()));
  EXPECT_EQ(rig.storage.bytes().size(), at[3]);
  EXPECT_EQ(rig.core->journal_records(), 3u);
}

TEST(StationRecovery, WhenTheTailCannotBeKeptNothingIsCut) {
  Rig rig;
  rig.write_moves(2);
  const std::array<std::byte, 5> torn{std::byte{40}};
  ASSERT_TRUE(rig.storage.append(torn).ok());
  const std::size_t size = rig.storage.bytes().size();
  test::FakeFileSink archive;
  archive.fail_next_commit();
  EXPECT_EQ(rig.station({&archive}).start().code(), StatusCode::io_error);
  EXPECT_EQ(rig.core->recovery().outcome, JournalRecovery::Outcome::tail_not_kept);
  EXPECT_EQ(rig.storage.bytes().size(), size);
}

// A checkpoint the station wrote at stop, for the journal as it stands.
std::vector<std::byte> checkpoint_of(Rig& rig) {
  test::FakeFileSink out;
  EXPECT_TRUE(rig.station({nullptr, nullptr, &out}).start().ok());
  rig.core->stop();
  EXPECT_EQ(rig.core->counters().events.checkpoints_written, 1u);
  return {out.bytes().begin(), out.bytes().end()};
}

JournalRecovery::Checkpoint restart_with(Rig& rig, const std::vector<std::byte>& checkpoint) {
  test::FakeStorage in;
  in.load(checkpoint);
  EXPECT_TRUE(rig.station({nullptr, &in, nullptr}).start().ok());
  return rig.core->recovery().checkpoint;
}

TEST(StationRecovery, ACheckpointIsUsedOnlyForItsJournalAndModel) {
  using C = JournalRecovery::Checkpoint;
  Rig rig;
  rig.write_moves(5);
  const auto checkpoint = checkpoint_of(rig);
  const math::Frame pose = rig.core->sculpt().object_pose();
  EXPECT_EQ(restart_with(rig, checkpoint), C::used);
  EXPECT_EQ(rig.core->recovery().checkpoint_records, 5u);
  EXPECT_EQ(rig.core->recovery().replayed, 0u);
  EXPECT_EQ(rig.core->sculpt().object_pose().origin, pose.origin);
  EXPECT_EQ(rig.core->journal_records(), 5u);
  EXPECT_EQ(rig.core->sculpt().next_sequence(), 5u);

  // More records after it: restored, then those replayed.
  Rig longer;
  longer.write_moves(8);
  EXPECT_EQ(restart_with(longer, checkpoint), C::used);
  EXPECT_EQ(longer.core->recovery().replayed, 3u);
  EXPECT_EQ(longer.core->sculpt().next_sequence(), 8u);

  // Another journal of the same length (other records), a shorter one, another model,
  // a damaged checkpoint: ignored, everything replayed.
  Rig other;
  other.write_moves(6);
  other.storage = test::FakeStorage();
  {
    journal::JournalWriter w(other.storage);
    ASSERT_TRUE(w.open().ok());
    for (std::uint32_t i = 0; i < 5; ++i) {
      journal::JournalRecord r;
      r.type = journal::RecordType::object_move;
      r.sequence = i;
      r.move.object_after.origin = {0.0, 0.2 * i, 0};
      ASSERT_TRUE(w.append(r).ok());
    }
  }
  EXPECT_EQ(restart_with(other, checkpoint), C::other_journal);
  EXPECT_EQ(other.core->recovery().replayed, 5u);
  Rig shorter;
  shorter.write_moves(4);
  EXPECT_EQ(restart_with(shorter, checkpoint), C::other_journal);
  Rig moved_model;
  moved_model.write_moves(5);
  moved_model.mesh.set_position(3, {9, 9, 9});
  EXPECT_EQ(restart_with(moved_model, checkpoint), C::other_model);
  Rig damaged;
  damaged.write_moves(5);
  auto flipped = checkpoint;
  flipped[flipped.size() / 2] ^= std::byte{1};
  EXPECT_EQ(restart_with(damaged, flipped), C::damaged);
  EXPECT_EQ(damaged.core->sculpt().object_pose().origin, pose.origin);  // by full replay
}

}  // namespace
}  // namespace twister::station
