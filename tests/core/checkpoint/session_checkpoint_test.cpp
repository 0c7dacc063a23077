// Session checkpoints (issue 11, item 10): a checkpoint plus the records after it
// rebuild exactly the model a full replay builds (mesh bit for bit, object pose, next
// sequence, undo history: undo across the checkpoint works the same), whatever the
// write budget; any damaged byte, another history size or a busy session is refused.
#include "twister/checkpoint/session_checkpoint.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "core/session/session_harness.hpp"
#include "fakes/fake_file_sink.hpp"

namespace twister::checkpoint {
namespace {

using namespace session::test_support;
using Sink = twister::test::FakeFileSinkWithStorage<1 << 20>;
constexpr double kPi = std::numbers::pi;

void stroke(Station& s, std::uint8_t hand, glm::dvec3 from, glm::dvec3 to, int freezes) {
  const std::uint8_t grab = hand == 0 ? kGrab0 : kGrab1;
  s.hand(hand, math::identity_frame(from));
  s.button(grab, true);
  (void)s.tick();
  for (int f = 1; f <= freezes + 1; ++f) {
    s.hand(hand, z_turn(from + (to - from) * (double(f) / (freezes + 1)), kPi / 3 * f));
    (void)s.tick();
    if (f <= freezes && hand == 1) {
      s.button(kFreeze1, true);
      (void)s.tick();
      s.button(kFreeze1, false);
      (void)s.tick();
    }
  }
  s.button(grab, false);
  (void)s.tick();
}

void move_object(Station& s) {
  s.hand(0, math::identity_frame({1, 1, 1}));
  s.button(kMove0, true);
  (void)s.tick();
  s.hand(0, z_turn({1.1, 0.9, 1.2}, 0.4));
  (void)s.tick();
  s.button(kMove0, false);
  (void)s.tick();
}

// Part 1 of the session: strokes, a freeze chain, a move, an undo.
void first_part(Station& s) {
  stroke(s, 0, {0, 0, 0}, {0.1, 0.05, 0.2}, 0);
  stroke(s, 1, {0.3, -0.2, 0}, {0.3, -0.1, 0.1}, 2);
  move_object(s);
  stroke(s, 0, {-0.3, 0.3, 0}, {-0.3, 0.3, -0.1}, 0);
  ASSERT_TRUE(s.session->undo().ok());
}

void second_part(Station& s) {
  stroke(s, 1, {0.1, 0.4, 0}, {0.2, 0.4, 0.1}, 1);
  ASSERT_TRUE(s.session->undo().ok());
  ASSERT_TRUE(s.session->redo().ok());
  stroke(s, 0, {-0.2, -0.4, 0}, {-0.2, -0.3, 0.1}, 0);
}

CheckpointAnchor anchor_of(Station& s) {
  return {s.writer.size(), s.session->next_sequence(), s.writer.last_crc()};
}

// The checkpoint of `s` as it stands, written with `budget` bytes per step.
void write_checkpoint(Station& s, Sink& sink, std::size_t budget) {
  CheckpointWriter writer(&sink);
  ASSERT_TRUE(writer.begin(*s.session, anchor_of(s), 42).ok());
  for (int i = 0; i < 100000; ++i) {
    const auto done = writer.step(*s.session, budget);
    ASSERT_TRUE(done.ok());
    if (*done) return;
  }
  FAIL() << "never finished";
}

// Applies the records of `storage` from offset `from` to `s`.
void replay_from(Station& s, TestStorage& storage, std::uint64_t from) {
  journal::JournalReader reader(storage);
  ASSERT_TRUE(reader.open().ok());
  if (from > 0) {
    ASSERT_TRUE(reader.seek(from).ok());
  }
  for (auto r = reader.next(); r.ok(); r = reader.next()) {
    ASSERT_TRUE(s.session->apply_record(*r).ok());
  }
}

void expect_same_model(Station& a, Station& b) {
  EXPECT_EQ(a.mesh.checksum(), b.mesh.checksum());
  EXPECT_EQ(a.session->object_pose().origin, b.session->object_pose().origin);
  EXPECT_EQ(a.session->object_pose().u, b.session->object_pose().u);
  EXPECT_EQ(a.session->next_sequence(), b.session->next_sequence());
  EXPECT_EQ(a.session->history().undo_depth(), b.session->history().undo_depth());
  EXPECT_EQ(a.session->history().redo_depth(), b.session->history().redo_depth());
}

TEST(SessionCheckpoint, CheckpointPlusTheRestIsBitIdenticalToAFullReplayAndUndoCrossesIt) {
  for (const std::size_t budget : {std::size_t{1}, std::size_t{5000}, std::size_t{1} << 30}) {
    SCOPED_TRACE(budget);
    auto live = std::make_unique<Station>();
    first_part(*live);
    Sink sink;
    write_checkpoint(*live, sink, budget);
    const std::uint64_t offset = live->writer.size();
    second_part(*live);

    auto full = std::make_unique<Station>(33, test_config(), false);
    replay_from(*full, live->storage, 0);
    expect_same_model(*live, *full);

    auto restored = std::make_unique<Station>(33, test_config(), false);
    TestStorage file;
    file.load(sink.bytes());
    const auto header = read_checkpoint_header(file);
    ASSERT_TRUE(header.ok());
    EXPECT_EQ(header->journal_offset, offset);
    EXPECT_EQ(header->base_checksum, 42u);
    ASSERT_TRUE(verify_checkpoint(file, *header, *restored->session).ok());
    ASSERT_TRUE(restore_checkpoint(file, *header, *restored->session).ok());
    replay_from(*restored, live->storage, offset);
    expect_same_model(*full, *restored);
    // Undo reaches back across the checkpoint, identically.
    for (int i = 0; i < 4; ++i) {
      const Status a = full->session->apply_record({journal::RecordType::undo, 0, {}, {}});
      const Status b = restored->session->apply_record({journal::RecordType::undo, 0, {}, {}});
      EXPECT_EQ(a.code(), b.code());
      expect_same_model(*full, *restored);
    }
  }
}

TEST(SessionCheckpoint, EveryDamagedByteIsRefusedWithoutTouchingTheSession) {
  auto live = std::make_unique<Station>(9);
  first_part(*live);
  Sink sink;
  write_checkpoint(*live, sink, 1 << 30);
  const std::vector<std::byte> good(sink.bytes().begin(), sink.bytes().end());
  auto target = std::make_unique<Station>(9, test_config(), false);
  const auto before = target->mesh.checksum();
  for (std::size_t i = 0; i < good.size(); i += 3) {
    TestStorage file;
    file.load(good);
    file.corrupt(i, std::byte{0x20});
    const auto header = read_checkpoint_header(file);
    if (header.ok()) {
      EXPECT_FALSE(verify_checkpoint(file, *header, *target->session).ok()) << i;
    }
  }
  EXPECT_EQ(target->mesh.checksum(), before);
  TestStorage cut;
  cut.load(std::span(good).first(good.size() - 1));
  EXPECT_FALSE(verify_checkpoint(cut, *read_checkpoint_header(cut), *target->session).ok());
}

TEST(SessionCheckpoint, AnotherMeshCapacityOrHistorySizeIsRefused) {
  auto live = std::make_unique<Station>(9);
  first_part(*live);
  Sink sink;
  write_checkpoint(*live, sink, 1 << 30);
  TestStorage file;
  file.load(sink.bytes());
  const auto header = read_checkpoint_header(file);
  ASSERT_TRUE(header.ok());
  auto smaller = std::make_unique<mesh::MeshWithStorage<kVertices / 2, kVertices>>();
  make_grid(*smaller, 9);
  auto other_capacity = std::make_unique<TestSession>(test_config(), *smaller, nullptr);
  EXPECT_EQ(verify_checkpoint(file, *header, *other_capacity).code(), StatusCode::data_loss);
  auto target = std::make_unique<Station>(9, test_config(), false);
  auto other_history =
      std::make_unique<session::SculptSessionWithStorage<kVertices, kVertices, 4096, 32>>(
          test_config(), target->mesh, nullptr);
  EXPECT_EQ(verify_checkpoint(file, *header, *other_history).code(), StatusCode::data_loss);
  // No triangle change pool (no refinement memory): another history size too.
  auto no_refinement =
      std::make_unique<session::SculptSessionWithStorage<kVertices, kVertices, 8192, 32>>(
          test_config(), target->mesh, nullptr);
  EXPECT_EQ(verify_checkpoint(file, *header, *no_refinement).code(), StatusCode::data_loss);
  // The model itself is the caller's check (base_checksum, compared by the station):
  // another start mesh of the same capacity verifies.
  auto other_model = std::make_unique<Station>(11, test_config(), false);
  EXPECT_TRUE(verify_checkpoint(file, *header, *other_model->session).ok());
}

TEST(SessionCheckpoint, NoCheckpointOfAnOpenStroke) {
  auto s = std::make_unique<Station>();
  s->hand(0, math::identity_frame({0, 0, 0}));
  s->button(kGrab0, true);
  (void)s->tick();
  Sink sink;
  CheckpointWriter writer(&sink);
  EXPECT_EQ(writer.begin(*s->session, anchor_of(*s), 0).code(), StatusCode::failed_precondition);
  CheckpointWriter none(nullptr);
  s->button(kGrab0, false);
  (void)s->tick();
  EXPECT_EQ(none.begin(*s->session, anchor_of(*s), 0).code(), StatusCode::failed_precondition);
}

}  // namespace
}  // namespace twister::checkpoint
