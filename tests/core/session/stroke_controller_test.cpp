#include "twister/session/stroke_controller.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <initializer_list>
#include <memory>

#include "parts_harness.hpp"

namespace twister::session {
namespace {

using namespace test_support;

// Keeps what the controller commits; changes no mesh.
class RecordingSink final : public StrokeCommitSink {
 public:
  std::array<journal::StrokeRecord, 128> records{};
  std::array<bool, 128> plan_goes_on{};  // per record: a freeze step (the plan is rebased)
  std::size_t count = 0;
  std::uint32_t next_sequence = 0;
  Status fail{};  // not ok: every commit fails with it

 private:
  CommitOutcome do_commit(const math::WarpPlan& plan, const journal::StrokeRecord& stroke,
                          SessionEvents& /*out*/, bool goes_on) override {
    if (!fail.ok()) return {fail, next_sequence};
    EXPECT_TRUE(plan.built());
    plan_goes_on[count] = goes_on;
    records[count++] = stroke;
    return {ok_status(), next_sequence++};
  }
};

template <std::size_t kInfluenced = 1024>
struct Strokes {
  SessionEvents step(std::initializer_list<input::Action> actions, float radius_m = 0.5f) {
    input::ActionList list;
    for (const input::Action& a : actions) list.push(a);
    SessionEvents out;
    strokes.begin_step(list, radius_m);
    for (const input::Action& a : list.items()) strokes.apply(a, out);
    strokes.end_step();
    return out;
  }
  void hand(std::uint8_t h, const math::Frame& f) {
    EXPECT_TRUE(rig.poses.set_hand(h, true, f).ok());
  }

  PartsRig<kInfluenced> rig;
  RecordingSink sink;
  StrokeController strokes{rig.plan, rig.live, rig.poses, sink, math::WarpMethod::twister};
};

input::Action act(input::ActionKind kind, std::uint8_t hand,
                  input::Reason reason = input::Reason::none) {
  return {kind, hand, reason, 0.0f};
}
input::Action grab(std::uint8_t h) { return act(input::ActionKind::grab_begin, h); }
input::Action release(std::uint8_t h) {
  return act(input::ActionKind::commit, h, input::Reason::released);
}
input::Action freeze(std::uint8_t h) { return act(input::ActionKind::freeze, h); }

constexpr std::uint32_t kCentre = 8 * 17 + 8;  // vertex at the origin of the 17 x 17 grid

TEST(StrokeController, GrabFollowReleaseCommitsOneSegment) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({0, 0, 0}));
  const SessionEvents begin = s->step({grab(0)});
  ASSERT_EQ(begin.items().size(), 1u);
  EXPECT_EQ(begin.items()[0].kind, SessionEventKind::grab_begin);
  EXPECT_TRUE(s->strokes.active());
  EXPECT_EQ(s->rig.plan.radius(), 0.5);
  s->hand(0, math::identity_frame({0, 0, 0.3}));
  EXPECT_EQ(s->step({}).items().size(), 0u);
  const LiveWarp live = s->strokes.live();
  EXPECT_TRUE(live.active);
  EXPECT_EQ(live.hand_mask, 1);
  EXPECT_EQ(live.plan, &s->rig.plan);
  EXPECT_NEAR(s->strokes.live_positions().z[kCentre], 0.3f, 1e-6f);
  EXPECT_EQ(s->rig.mesh.position(kCentre).z, 0.0f);  // committing is the sink's

  const SessionEvents done = s->step({release(0)});
  ASSERT_EQ(done.items().size(), 1u);
  EXPECT_EQ(done.items()[0].kind, SessionEventKind::committed);
  EXPECT_EQ(done.items()[0].stroke_end().reason, input::Reason::released);
  EXPECT_EQ(done.items()[0].stroke_end().sequence, 0u);
  ASSERT_EQ(s->sink.count, 1u);
  const journal::StrokeRecord& r = s->sink.records[0];
  EXPECT_EQ(r.hand_mask, 1);
  EXPECT_EQ(r.chain_step, 0);
  EXPECT_EQ(r.radius_m, 0.5);
  EXPECT_EQ(r.start[0].origin, glm::dvec3(0, 0, 0));
  EXPECT_EQ(r.end[0].origin, glm::dvec3(0, 0, 0.3));
  EXPECT_FALSE(s->strokes.active());
  EXPECT_FALSE(s->rig.plan.built());
}

TEST(StrokeController, FreezeCommitsAndGoesOnWithTheNextChainStep) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(1, z_turn({0, 0, 0}, 0.0));
  (void)s->step({grab(1)});
  s->hand(1, z_turn({0, 0, 0}, 1.0));
  (void)s->step({});
  const SessionEvents frozen = s->step({freeze(1)});
  ASSERT_EQ(frozen.items().size(), 2u);
  EXPECT_EQ(frozen.items()[0].kind, SessionEventKind::committed);
  EXPECT_EQ(frozen.items()[0].stroke_end().reason, input::Reason::none);  // the stroke goes on
  EXPECT_EQ(frozen.items()[1].kind, SessionEventKind::disengaged);        // the clutch is in
  EXPECT_TRUE(s->strokes.active());
  EXPECT_EQ(s->strokes.chain_step(), 1);
  (void)s->step({act(input::ActionKind::unfreeze, 1)});  // the clutch is out again, same pose
  s->hand(1, z_turn({0, 0, 0}, 2.0));
  (void)s->step({});
  (void)s->step({release(1)});
  ASSERT_EQ(s->sink.count, 2u);
  const journal::StrokeRecord& first = s->sink.records[0];
  const journal::StrokeRecord& second = s->sink.records[1];
  EXPECT_EQ(first.hand_mask, 2);
  EXPECT_EQ(first.chain_step, 0);
  EXPECT_EQ(second.chain_step, 1);
  EXPECT_EQ(second.start[1], first.end[1]);  // the freeze point
  EXPECT_NEAR(second.end[1].u.x, std::cos(2.0), 1e-12);
}

TEST(StrokeController, AJoiningHandCommitsWhatTheFirstHandDid) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({-0.5, 0, 0}));
  s->hand(1, math::identity_frame({0.5, 0, 0}));
  (void)s->step({grab(0)});
  s->hand(0, math::identity_frame({-0.5, 0, 0.2}));
  (void)s->step({});
  const SessionEvents join = s->step({grab(1)});
  ASSERT_EQ(join.items().size(), 2u);
  EXPECT_EQ(join.items()[0].kind, SessionEventKind::committed);
  EXPECT_EQ(join.items()[0].hand, 1);
  EXPECT_EQ(join.items()[1].kind, SessionEventKind::grab_begin);
  ASSERT_EQ(s->sink.count, 1u);
  EXPECT_EQ(s->sink.records[0].hand_mask, 1);
  EXPECT_EQ(s->strokes.hand_mask(), 3);
  EXPECT_EQ(s->rig.plan.hand_count(), 2u);
  EXPECT_EQ(s->rig.plan.start_frame(0).origin, glm::dvec3(-0.5, 0, 0.2));  // from here on
}

TEST(StrokeController, HandsGrabbingInTheSameStepStartTogether) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({-0.5, 0, 0}));
  s->hand(1, math::identity_frame({0.5, 0, 0}));
  const SessionEvents begin = s->step({grab(0), grab(1)});
  EXPECT_EQ(count_events(begin, SessionEventKind::grab_begin), 2u);
  EXPECT_EQ(count_events(begin, SessionEventKind::committed), 0u);
  EXPECT_EQ(s->strokes.hand_mask(), 3);
}

TEST(StrokeController, HandsReleasedTogetherShareOneCommit) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({-0.5, 0, 0}));
  s->hand(1, math::identity_frame({0.5, 0, 0}));
  (void)s->step({grab(0), grab(1)});
  s->hand(1, math::identity_frame({0.5, 0, 0.1}));
  (void)s->step({});
  const SessionEvents done = s->step({release(0), release(1)});
  ASSERT_EQ(done.items().size(), 2u);
  for (std::uint8_t h = 0; h < 2; ++h) {
    EXPECT_EQ(done.items()[h].kind, SessionEventKind::committed);
    EXPECT_EQ(done.items()[h].hand, h);
    EXPECT_EQ(done.items()[h].stroke_end().reason, input::Reason::released);
    EXPECT_EQ(done.items()[h].stroke_end().sequence, 0u);
  }
  ASSERT_EQ(s->sink.count, 1u);
  EXPECT_EQ(s->sink.records[0].hand_mask, 3);
  EXPECT_FALSE(s->strokes.active());
}

TEST(StrokeController, AHandLeavingLeavesTheOtherInANewSegment) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({-0.5, 0, 0}));
  s->hand(1, math::identity_frame({0.5, 0, 0}));
  (void)s->step({grab(0), grab(1)});
  s->hand(0, math::identity_frame({-0.5, 0, 0.1}));
  (void)s->step({});
  const SessionEvents left = s->step({release(0)});
  ASSERT_EQ(left.items().size(), 1u);
  EXPECT_EQ(left.items()[0].hand, 0);
  ASSERT_EQ(s->sink.count, 1u);
  EXPECT_EQ(s->sink.records[0].hand_mask, 3);
  EXPECT_EQ(s->strokes.hand_mask(), 2);
  EXPECT_EQ(s->strokes.chain_step(), 0);
  EXPECT_EQ(s->rig.plan.hand_count(), 1u);
}

TEST(StrokeController, CancelDropsOnlyTheOpenSegment) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(1, z_turn({0, 0, 0}, 0.0));
  (void)s->step({grab(1)});
  s->hand(1, z_turn({0, 0, 0}, 0.5));
  (void)s->step({freeze(1)});
  s->hand(1, z_turn({0, 0, 0}, 1.0));
  (void)s->step({});
  const SessionEvents cancelled =
      s->step({act(input::ActionKind::cancel, 1, input::Reason::tracking_timeout)});
  ASSERT_EQ(cancelled.items().size(), 1u);
  EXPECT_EQ(cancelled.items()[0].kind, SessionEventKind::cancelled);
  EXPECT_EQ(cancelled.items()[0].stroke_end().reason, input::Reason::tracking_timeout);
  EXPECT_EQ(s->sink.count, 1u);  // the freeze step stays committed
  EXPECT_FALSE(s->strokes.active());
}

TEST(StrokeController, APlanErrorRefusesTheGrab) {
  auto s = std::make_unique<Strokes<4>>();  // room for 4 influenced vertices
  s->hand(0, math::identity_frame({0, 0, 0}));
  const SessionEvents refused = s->step({grab(0)});
  ASSERT_EQ(refused.items().size(), 1u);
  EXPECT_EQ(refused.items()[0].kind, SessionEventKind::refused);
  EXPECT_EQ(refused.items()[0].status.code(), StatusCode::resource_exhausted);
  EXPECT_FALSE(s->strokes.active());
}

// The second hand does not fit the plan: it is refused and the first hand goes on.
TEST(StrokeController, ARefusedJoinKeepsTheFirstHandGoing) {
  auto s = std::make_unique<Strokes<80>>();
  s->hand(0, math::identity_frame({-0.6, 0, 0}));
  s->hand(1, math::identity_frame({0.6, 0, 0}));
  ASSERT_EQ(s->step({grab(0)}).items()[0].kind, SessionEventKind::grab_begin);
  s->hand(0, math::identity_frame({-0.6, 0, 0.1}));
  (void)s->step({});
  const SessionEvents join = s->step({grab(1)});
  ASSERT_EQ(join.items().size(), 2u);
  EXPECT_EQ(join.items()[0].kind, SessionEventKind::committed);
  EXPECT_EQ(join.items()[1].kind, SessionEventKind::refused);
  EXPECT_EQ(join.items()[1].hand, 1);
  EXPECT_EQ(s->strokes.hand_mask(), 1);
  EXPECT_EQ(s->rig.plan.hand_count(), 1u);
}

TEST(StrokeController, ActionsOfHandsNotInTheStrokeAreIgnored) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({0, 0, 0}));
  EXPECT_EQ(s->step({freeze(0), release(1), act(input::ActionKind::move_begin, 0)}).items().size(),
            0u);
  (void)s->step({grab(0)});
  EXPECT_EQ(s->step({freeze(1), release(1)}).items().size(), 0u);
  EXPECT_EQ(s->sink.count, 0u);
  EXPECT_EQ(s->strokes.hand_mask(), 1);
}

TEST(StrokeController, HandPosesAreTakenInTheObjectFrame) {
  auto s = std::make_unique<Strokes<>>();
  s->rig.poses.set_object(math::identity_frame({1, 0, 0}));
  s->hand(0, math::identity_frame({1, 0, 0}));
  (void)s->step({grab(0)});
  s->hand(0, math::identity_frame({1, 0, 0.2}));
  (void)s->step({});
  (void)s->step({release(0)});
  ASSERT_EQ(s->sink.count, 1u);
  EXPECT_EQ(s->sink.records[0].start[0].origin, glm::dvec3(0, 0, 0));
  EXPECT_EQ(s->sink.records[0].end[0].origin, glm::dvec3(0, 0, 0.2));
}

// Issue 11 changed this: a commit that did not happen is `not_saved`, never `committed`.
TEST(StrokeController, AFailedCommitIsReportedAsNotSaved) {
  auto s = std::make_unique<Strokes<>>();
  s->sink.fail = Status(StatusCode::invalid_argument);
  s->hand(0, math::identity_frame({0, 0, 0}));
  (void)s->step({grab(0)});
  const SessionEvents done = s->step({release(0)});
  ASSERT_EQ(done.items().size(), 1u);
  EXPECT_EQ(done.items()[0].kind, SessionEventKind::not_saved);
  EXPECT_EQ(done.items()[0].stroke_end().reason, input::Reason::released);
  EXPECT_EQ(done.items()[0].status.code(), StatusCode::invalid_argument);
  EXPECT_FALSE(s->strokes.active());
}

// A freeze whose commit is not saved ends the stroke for every hand of it: the chain
// cannot go on over a step the model does not hold, so no chain step is ever skipped.
// Merge of issue 12 (the clutch): a freeze press now also reports `disengaged` and a
// hand on the clutch ignores another press, so the failing freeze is hand 0's while
// hand 1 is still on the clutch (its stroke ends too).
TEST(StrokeController, AFreezeThatIsNotSavedEndsTheStrokeAndTheChain) {
  auto s = std::make_unique<Strokes<>>();
  s->hand(0, math::identity_frame({-0.3, 0, 0}));
  s->hand(1, math::identity_frame({0.3, 0, 0}));
  (void)s->step({grab(0), grab(1)});
  s->hand(1, math::identity_frame({0.3, 0, 0.1}));
  (void)s->step({});
  ASSERT_EQ(s->step({freeze(1)}).items().size(), 2u);  // chain step 0 saved, disengaged
  s->sink.fail = Status(StatusCode::io_error);
  s->hand(0, math::identity_frame({-0.3, 0, 0.2}));
  (void)s->step({});
  const SessionEvents failed = s->step({freeze(0)});
  ASSERT_EQ(failed.items().size(), 2u);
  for (const SessionEvent& e : failed.items()) {
    EXPECT_EQ(e.kind, SessionEventKind::not_saved);
    EXPECT_EQ(e.stroke_end().reason, input::Reason::released);
    EXPECT_EQ(e.status.code(), StatusCode::io_error);
  }
  EXPECT_NE(failed.items()[0].hand, failed.items()[1].hand);
  EXPECT_FALSE(s->strokes.active());
  // The disk is back: the next stroke starts a new chain (step 0), never step 2.
  s->sink.fail = Status{};
  (void)s->step({release(0), release(1)});  // the machine's releases find nothing open
  (void)s->step({grab(1)});
  s->hand(1, math::identity_frame({0.3, 0, 0.3}));
  (void)s->step({});
  (void)s->step({release(1)});
  ASSERT_EQ(s->sink.count, 2u);
  EXPECT_EQ(s->sink.records[0].chain_step, 0);
  EXPECT_EQ(s->sink.records[1].chain_step, 0);
}

// Random stroke actions in the machine's order (hand 0's, then hand 1's): every grab
// ends exactly once, the controller's hands are the grabbing hands, and a record with
// chain step k > 0 directly follows step k - 1 of the same hands.
RC_GTEST_PROP(StrokeControllerProperty, GrabsEndOnceAndChainsFollowEachOther, ()) {
  auto s = std::make_unique<Strokes<>>();
  const int steps = *rc::gen::inRange(10, 60);
  std::array<bool, 2> open{};
  for (int i = 0; i < steps; ++i) {
    input::ActionList actions;
    for (std::uint8_t h = 0; h < 2; ++h) {
      const double side = h == 0 ? -0.5 : 0.5;
      s->hand(h, z_turn({side + *rc::gen::inRange(-10, 10) / 100.0, 0, 0.01 * i},
                        *rc::gen::inRange(-30, 30) / 10.0));
      const int roll = *rc::gen::inRange(0, 20);
      if (!open[h] && roll < 4) actions.push(grab(h));
      if (open[h] && roll < 2) actions.push(freeze(h));
      if (open[h] && roll >= 2 && roll < 5) actions.push(release(h));
      if (open[h] && roll == 5)
        actions.push(act(input::ActionKind::cancel, h, input::Reason::tracking_timeout));
    }
    const std::size_t records_before = s->sink.count;
    SessionEvents out;
    s->strokes.begin_step(actions, 0.5f);
    for (const input::Action& a : actions.items()) s->strokes.apply(a, out);
    s->strokes.end_step();
    for (const SessionEvent& e : out.items()) {
      RC_ASSERT(e.status.ok());
      if (e.kind == SessionEventKind::grab_begin) {
        RC_ASSERT(!open[e.hand]);
        open[e.hand] = true;
      }
      const bool ends = e.kind == SessionEventKind::cancelled ||
                        (e.kind == SessionEventKind::committed &&
                         e.stroke_end().reason == input::Reason::released);
      if (ends) {
        RC_ASSERT(open[e.hand]);
        open[e.hand] = false;
      }
    }
    const auto mask = static_cast<std::uint8_t>((open[0] ? 1 : 0) | (open[1] ? 2 : 0));
    RC_ASSERT(s->strokes.hand_mask() == mask);
    for (std::size_t k = std::max<std::size_t>(records_before, 1); k < s->sink.count; ++k) {
      const journal::StrokeRecord& r = s->sink.records[k];
      if (r.chain_step == 0) continue;
      RC_ASSERT(s->sink.records[k - 1].chain_step + 1 == r.chain_step);
      RC_ASSERT(s->sink.records[k - 1].hand_mask == r.hand_mask);
    }
  }
}

}  // namespace
}  // namespace twister::session
