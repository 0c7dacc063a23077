#include "twister/session/session_history.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "parts_harness.hpp"

namespace twister::session {
namespace {

using namespace test_support;

template <class Rig>
void build_lift(Rig& r, double lift_m) {
  const math::Frame start = math::identity_frame({0, 0, 0});
  ASSERT_TRUE(
      r.plan.build(r.live.rest(), std::span(&start, 1), 0.5, math::WarpMethod::twister).ok());
  const math::Frame end = math::identity_frame({0, 0, lift_m});
  ASSERT_TRUE(r.plan.update(std::span(&end, 1)).ok());
}

journal::StrokeRecord one_hand_stroke() {
  journal::StrokeRecord s;
  s.hand_mask = 1;
  s.radius_m = 0.5;
  s.end[0].origin = {0, 0, 0.25};
  return s;
}

TEST(SessionHistory, AStrokeCommitMovesTheMeshAndWritesOneRecord) {
  auto r = std::make_unique<PartsRig<>>();
  build_lift(*r, 0.25);
  SessionEvents out;
  StrokeCommitSink& sink = r->history;
  const CommitOutcome done = sink.commit(r->plan, one_hand_stroke(), out);
  EXPECT_TRUE(done.status.ok());
  EXPECT_EQ(done.sequence, 0u);
  EXPECT_EQ(out.items().size(), 0u);  // the committed event is the caller's
  EXPECT_EQ(r->history.next_sequence(), 1u);
  EXPECT_NEAR(r->mesh.position(8 * 17 + 8).z, 0.25f, 1e-6f);  // the centre vertex
  for (const std::uint32_t i : r->plan.indices()) {
    EXPECT_EQ(r->mesh.position(i).z, r->live_z[i]);
  }
  EXPECT_EQ(r->history.undo_history().undo_depth(), 1u);
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(r->read_records(records), 1u);
  EXPECT_EQ(records[0].type, journal::RecordType::stroke);
  EXPECT_EQ(records[0].sequence, 0u);
  EXPECT_EQ(records[0].stroke, one_hand_stroke());
}

TEST(SessionHistory, UndoAndRedoAreJournaledAndExact) {
  auto r = std::make_unique<PartsRig<>>();
  const auto original = r->mesh.checksum();
  build_lift(*r, 0.25);
  SessionEvents out;
  ASSERT_TRUE(static_cast<StrokeCommitSink&>(r->history)
                  .commit(r->plan, one_hand_stroke(), out)
                  .status.ok());
  const auto lifted = r->mesh.checksum();
  ASSERT_TRUE(r->history.commit_history_step(journal::RecordType::undo).ok());
  EXPECT_EQ(r->mesh.checksum(), original);
  ASSERT_TRUE(r->history.commit_history_step(journal::RecordType::redo).ok());
  EXPECT_EQ(r->mesh.checksum(), lifted);
  EXPECT_EQ(r->history.commit_history_step(journal::RecordType::redo).code(),
            StatusCode::failed_precondition);
  EXPECT_EQ(r->history.next_sequence(), 3u);  // stroke, undo, redo; not the refused redo
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(r->read_records(records), 3u);
  EXPECT_EQ(records[1].type, journal::RecordType::undo);
  EXPECT_EQ(records[1].sequence, 1u);
  EXPECT_EQ(records[2].type, journal::RecordType::redo);
}

TEST(SessionHistory, AMoveIsRecordedAndUndoPutsTheObjectBack) {
  auto r = std::make_unique<PartsRig<>>();
  const math::Frame before = r->poses.object();
  const math::Frame after = z_turn({1, 2, 3}, 0.5);
  r->poses.set_object(after);  // the mover has moved it
  const CommitOutcome done = r->history.commit_move(1, before, after);
  EXPECT_TRUE(done.status.ok());
  EXPECT_EQ(done.sequence, 0u);
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(r->read_records(records), 1u);
  EXPECT_EQ(records[0].type, journal::RecordType::object_move);
  EXPECT_EQ(records[0].move.hand, 1);
  EXPECT_EQ(records[0].move.object_after.origin, after.origin);
  ASSERT_TRUE(r->history.commit_history_step(journal::RecordType::undo).ok());
  EXPECT_EQ(r->poses.object().origin, before.origin);
  ASSERT_TRUE(r->history.commit_history_step(journal::RecordType::redo).ok());
  EXPECT_EQ(r->poses.object().origin, after.origin);
}

TEST(SessionHistory, ACommitTooLargeForTheHistoryStandsButIsNotUndoable) {
  auto r = std::make_unique<PartsRig<1024, 8, 4>>();  // 8 vertex changes in all
  build_lift(*r, 0.25);
  ASSERT_GT(r->plan.indices().size(), 8u);
  SessionEvents out;
  const CommitOutcome done =
      static_cast<StrokeCommitSink&>(r->history).commit(r->plan, one_hand_stroke(), out);
  EXPECT_TRUE(done.status.ok());
  ASSERT_EQ(count_events(out, SessionEventKind::history_overflow), 1u);
  EXPECT_EQ(out.items()[0].record().sequence, done.sequence);
  EXPECT_NEAR(r->mesh.position(8 * 17 + 8).z, 0.25f, 1e-6f);
  EXPECT_FALSE(r->history.undo_history().can_undo());
  EXPECT_EQ(r->history.next_sequence(), 1u);  // journaled all the same
}

// Issue 11 changed this: a commit whose record is not durable is not made (write-ahead).
TEST(SessionHistory, ACommitWhoseRecordIsNotDurableIsNotMade) {
  auto r = std::make_unique<PartsRig<>>();
  const auto original = r->mesh.checksum();
  build_lift(*r, 0.25);
  r->storage.fail_next_sync();
  SessionEvents out;
  const CommitOutcome done =
      static_cast<StrokeCommitSink&>(r->history).commit(r->plan, one_hand_stroke(), out);
  EXPECT_EQ(done.status.code(), StatusCode::io_error);
  EXPECT_EQ(done.sequence, 0u);
  EXPECT_TRUE(out.items().empty());
  EXPECT_EQ(r->mesh.checksum(), original);  // the model is the last durable one
  EXPECT_EQ(r->history.next_sequence(), 0u);
  EXPECT_FALSE(r->history.undo_history().can_undo());
  std::array<journal::JournalRecord, 16> records{};
  EXPECT_EQ(r->read_records(records), 0u);  // the failed record was cut off again
  // The next commit takes the sequence the failed one could not use.
  const CommitOutcome again =
      static_cast<StrokeCommitSink&>(r->history).commit(r->plan, one_hand_stroke(), out);
  ASSERT_TRUE(again.status.ok());
  EXPECT_EQ(again.sequence, 0u);
  EXPECT_NEAR(r->mesh.position(8 * 17 + 8).z, 0.25f, 1e-6f);
  ASSERT_EQ(r->read_records(records), 1u);
  EXPECT_EQ(records[0].sequence, 0u);
}

TEST(SessionHistory, AnUndoWhoseRecordIsNotDurableIsTakenBack) {
  auto r = std::make_unique<PartsRig<>>();
  build_lift(*r, 0.25);
  SessionEvents out;
  ASSERT_TRUE(static_cast<StrokeCommitSink&>(r->history)
                  .commit(r->plan, one_hand_stroke(), out)
                  .status.ok());
  const auto committed = r->mesh.checksum();
  // Power gone: the undo's record cannot be written, and the partial record cannot be
  // cut off (the writer is broken): the undo is taken back.
  r->storage.cut_power_after(3);
  EXPECT_EQ(r->history.commit_history_step(journal::RecordType::undo).code(), StatusCode::io_error);
  EXPECT_EQ(r->mesh.checksum(), committed);
  EXPECT_TRUE(r->history.undo_history().can_undo());
  EXPECT_EQ(r->history.next_sequence(), 1u);
  EXPECT_FALSE(r->writer.healthy());
  // Power back: the writer repairs the file before the next record.
  r->storage.power_on();
  ASSERT_TRUE(r->history.commit_history_step(journal::RecordType::undo).ok());
  EXPECT_TRUE(r->writer.healthy());
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(r->read_records(records), 2u);
  EXPECT_EQ(records[1].type, journal::RecordType::undo);
  EXPECT_EQ(records[1].sequence, 1u);
}

TEST(SessionHistory, AMoveWhoseRecordIsNotDurablePutsTheObjectBack) {
  auto r = std::make_unique<PartsRig<>>();
  const math::Frame before = r->poses.object();
  const math::Frame after = math::identity_frame({0.5, 0, 0});
  r->poses.set_object(after);  // where the mover left it
  r->storage.fail_next_sync();
  const CommitOutcome done = r->history.commit_move(0, before, after);
  EXPECT_EQ(done.status.code(), StatusCode::io_error);
  EXPECT_EQ(r->poses.object().origin, before.origin);
  EXPECT_FALSE(r->history.undo_history().can_undo());
  EXPECT_EQ(r->history.next_sequence(), 0u);
}

TEST(SessionHistory, APlanThatCannotApplyCommitsNothing) {
  auto r = std::make_unique<PartsRig<>>();
  const auto original = r->mesh.checksum();
  SessionEvents out;
  const CommitOutcome done =  // never built
      static_cast<StrokeCommitSink&>(r->history).commit(r->plan, one_hand_stroke(), out);
  EXPECT_EQ(done.status.code(), StatusCode::failed_precondition);
  EXPECT_EQ(done.sequence, 0u);
  EXPECT_EQ(r->history.next_sequence(), 0u);
  EXPECT_EQ(r->mesh.checksum(), original);
  EXPECT_FALSE(r->history.undo_history().can_undo());
}

TEST(SessionHistory, TheReplayPathChangesTheModelWithoutRecords) {
  auto r = std::make_unique<PartsRig<>>();
  build_lift(*r, 0.25);
  ASSERT_TRUE(r->history.apply_stroke(r->plan).ok());
  r->history.apply_move(r->poses.object(), math::identity_frame({0, 0, 1}));
  EXPECT_NEAR(r->mesh.position(8 * 17 + 8).z, 0.25f, 1e-6f);
  EXPECT_EQ(r->history.undo_history().undo_depth(), 2u);
  ASSERT_TRUE(r->history.apply_history_step(journal::RecordType::undo).ok());
  EXPECT_EQ(r->history.next_sequence(), 0u);
  std::array<journal::JournalRecord, 16> records{};
  EXPECT_EQ(r->read_records(records), 0u);
  r->history.resume_after(41);
  EXPECT_EQ(r->history.next_sequence(), 42u);
}

}  // namespace
}  // namespace twister::session
