#include "twister/session/journal_replay.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "parts_harness.hpp"
#include "twister/session/stroke_controller.hpp"

namespace twister::session {
namespace {

using namespace test_support;

// A rig with the parts a replay needs, plus a stroke controller to record live.
struct ReplayRig {
  PartsRig<> rig;
  JournalReplay replay{rig.plan, rig.live, rig.history, rig.poses};
  StrokeController strokes{rig.plan, rig.live, rig.poses, rig.history, math::WarpMethod::twister};

  // One stroke of hand 1 turning about z by `turn` in `freezes` + 1 equal steps.
  void stroke(double turn, int freezes) {
    EXPECT_TRUE(rig.poses.set_hand(1, true, z_turn({0.1, 0, 0}, 0)).ok());
    act(input::ActionKind::grab_begin);
    for (int k = 1; k <= freezes + 1; ++k) {
      EXPECT_TRUE(rig.poses.set_hand(1, true, z_turn({0.1, 0, 0}, turn * k / (freezes + 1))).ok());
      strokes.end_step();  // a step without actions: the plan follows the hand
      if (k <= freezes) {  // the clutch: press (commit, disengage) and release (re-engage)
        act(input::ActionKind::freeze);
        act(input::ActionKind::unfreeze);
      }
    }
    act(input::ActionKind::commit);
  }
  // A step with one action of hand 1.
  void act(input::ActionKind kind) {
    const input::Action a{
        kind, 1, kind == input::ActionKind::commit ? input::Reason::released : input::Reason::none,
        0.0f};
    input::ActionList list;
    list.push(a);
    SessionEvents out;
    strokes.begin_step(list, 0.6f);
    strokes.apply(a, out);
    strokes.end_step();
  }
};

journal::JournalRecord freeze_step_record(std::uint16_t chain_step) {
  journal::JournalRecord r;
  r.type = journal::RecordType::stroke;
  r.stroke.hand_mask = 2;
  r.stroke.chain_step = chain_step;
  r.stroke.radius_m = 0.6;
  return r;
}

TEST(JournalReplay, AFrozenStrokeAndAMoveReplayToTheSameModel) {
  auto live = std::make_unique<ReplayRig>();
  live->stroke(2.0, 2);
  const math::Frame moved = z_turn({0.5, 0.25, 0}, 0.5);
  (void)live->rig.history.commit_move(0, live->rig.poses.object(), moved);
  live->rig.poses.set_object(moved);
  ASSERT_TRUE(live->rig.history.commit_history_step(journal::RecordType::undo).ok());
  std::array<journal::JournalRecord, 16> records{};
  const std::size_t n = live->rig.read_records(records);
  ASSERT_EQ(n, 5u);  // three chained strokes, the move, the undo

  auto again = std::make_unique<ReplayRig>();
  for (std::size_t i = 0; i < n; ++i) ASSERT_TRUE(again->replay.apply(records[i]).ok()) << i;
  EXPECT_EQ(again->rig.mesh.checksum(), live->rig.mesh.checksum());
  EXPECT_EQ(again->rig.poses.object().origin, live->rig.poses.object().origin);
  EXPECT_EQ(again->rig.history.next_sequence(), 5u);
  EXPECT_EQ(again->replay.stats().strokes, 3u);
  EXPECT_EQ(again->replay.stats().moves, 1u);
  EXPECT_EQ(again->replay.stats().undos, 1u);
  EXPECT_EQ(again->replay.stats().redos, 0u);
  std::array<journal::JournalRecord, 16> written{};
  EXPECT_EQ(again->rig.read_records(written), 0u);  // replay writes no records
}

TEST(JournalReplay, AFreezeStepNeedsItsChain) {
  auto r = std::make_unique<ReplayRig>();
  EXPECT_EQ(r->replay.apply(freeze_step_record(1)).code(), StatusCode::data_loss);
  r->stroke(1.0, 0);  // live: the plan is reset afterwards
  EXPECT_EQ(r->replay.apply(freeze_step_record(1)).code(), StatusCode::data_loss);
  EXPECT_EQ(r->replay.stats().strokes, 0u);
}

TEST(JournalReplay, AChainBrokenByAnUndoCannotContinue) {
  auto live = std::make_unique<ReplayRig>();
  live->stroke(1.5, 1);
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(live->rig.read_records(records), 2u);
  ASSERT_EQ(records[1].stroke.chain_step, 1);

  auto a = std::make_unique<ReplayRig>();
  ASSERT_TRUE(a->replay.apply(records[0]).ok());
  a->replay.break_chain();  // e.g. a live undo in between
  EXPECT_EQ(a->replay.apply(records[1]).code(), StatusCode::data_loss);

  auto b = std::make_unique<ReplayRig>();
  ASSERT_TRUE(b->replay.apply(records[0]).ok());
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  undo.sequence = 1;
  ASSERT_TRUE(b->replay.apply(undo).ok());
  EXPECT_EQ(b->replay.apply(records[1]).code(), StatusCode::data_loss);

  auto c = std::make_unique<ReplayRig>();  // the chain in order: fine
  ASSERT_TRUE(c->replay.apply(records[0]).ok());
  EXPECT_TRUE(c->replay.apply(records[1]).ok());
  EXPECT_EQ(c->rig.mesh.checksum(), live->rig.mesh.checksum());
}

TEST(JournalReplay, AFreezeStepWithOtherHandsOrRadiusIsRejected) {
  auto live = std::make_unique<ReplayRig>();
  live->stroke(1.5, 1);
  std::array<journal::JournalRecord, 16> records{};
  ASSERT_EQ(live->rig.read_records(records), 2u);
  journal::JournalRecord other_radius = records[1];
  other_radius.stroke.radius_m = 0.7;
  journal::JournalRecord other_hands = records[1];
  other_hands.stroke.hand_mask = 3;
  for (const journal::JournalRecord& bad : {other_radius, other_hands}) {
    auto r = std::make_unique<ReplayRig>();
    ASSERT_TRUE(r->replay.apply(records[0]).ok());
    EXPECT_EQ(r->replay.apply(bad).code(), StatusCode::data_loss);
  }
}

TEST(JournalReplay, ErrorsApplyNothingAndKeepTheSequence) {
  auto r = std::make_unique<ReplayRig>();
  const auto original = r->rig.mesh.checksum();
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  undo.sequence = 7;
  EXPECT_EQ(r->replay.apply(undo).code(), StatusCode::data_loss);  // empty history
  journal::JournalRecord move;
  move.type = journal::RecordType::object_move;
  move.sequence = 8;
  move.move.object_after.u = {2, 0, 0};  // not orthonormal
  EXPECT_EQ(r->replay.apply(move).code(), StatusCode::data_loss);
  journal::JournalRecord stroke = freeze_step_record(0);
  stroke.sequence = 9;
  stroke.stroke.radius_m = -1.0;  // the plan refuses it
  EXPECT_EQ(r->replay.apply(stroke).code(), StatusCode::invalid_argument);
  EXPECT_EQ(r->rig.history.next_sequence(), 0u);
  EXPECT_EQ(r->rig.mesh.checksum(), original);
  EXPECT_EQ(r->replay.stats().undos + r->replay.stats().moves + r->replay.stats().strokes, 0u);
}

TEST(JournalReplay, RecordsKeepTheirSequenceNumbers) {
  auto r = std::make_unique<ReplayRig>();
  journal::JournalRecord move;
  move.type = journal::RecordType::object_move;
  move.sequence = 41;
  move.move.object_after.origin = {0, 0, 1};
  ASSERT_TRUE(r->replay.apply(move).ok());
  EXPECT_EQ(r->rig.history.next_sequence(), 42u);
  EXPECT_EQ(r->rig.poses.object().origin, glm::dvec3(0, 0, 1));
  ASSERT_TRUE(r->rig.history.commit_history_step(journal::RecordType::undo).ok());
  EXPECT_EQ(r->rig.poses.object().origin, glm::dvec3(0.0));
}

}  // namespace
}  // namespace twister::session
