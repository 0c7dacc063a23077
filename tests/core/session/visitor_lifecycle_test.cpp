// The exhibit's visitor lifecycle (issue 25): attract -> sculpting -> finished ->
// attract, idle and chord ends, the grace and its undo, failed archives retried.
// Examples, then a rapidcheck property over random inputs, times and commands.
// Label exhibit.
#include "twister/session/visitor_lifecycle.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace twister::session {
namespace {

constexpr ports::TimestampUs kS = 1'000'000;

VisitorConfig config() {
  VisitorConfig c;
  c.enabled = true;
  c.idle_us = 60 * kS;
  c.grace_us = 5 * kS;
  c.chord_hold_us = kS + kS / 2;
  c.retry_us = 3 * kS;
  c.motion_threshold_m = 0.02;
  return c;
}

VisitorInputs still() {
  VisitorInputs in;
  in.tracked = {true, true};
  in.hand_m = {{{0.1, 0.0, 0.2}, {-0.1, 0.0, 0.2}}};
  return in;
}

VisitorInputs grabbing() {
  VisitorInputs in = still();
  in.active = true;
  return in;
}

TEST(VisitorLifecycle, OffItNeverActs) {
  VisitorLifecycle life(VisitorConfig{});
  life.start(true, 0);
  VisitorInputs in = still();
  in.chord_held = true;
  for (ports::TimestampUs t = 0; t < 1000 * kS; t += 10 * kS) {
    EXPECT_EQ(life.step(in, t), VisitorAction::none);
  }
  EXPECT_EQ(life.request_new(0), VisitorAction::refused);
  EXPECT_EQ(life.request_undo(0), VisitorAction::refused);
}

TEST(VisitorLifecycle, FirstGrabBeginsIdleEndsGraceArchivesBackToAttract) {
  VisitorLifecycle life(config());
  life.start(false, 0);
  EXPECT_EQ(life.phase(), VisitorPhase::attract);
  EXPECT_EQ(life.step(still(), kS), VisitorAction::none);  // hands waving do not begin
  EXPECT_EQ(life.step(grabbing(), 2 * kS), VisitorAction::began);
  EXPECT_EQ(life.phase(), VisitorPhase::sculpting);
  EXPECT_EQ(life.step(still(), 3 * kS), VisitorAction::none);
  EXPECT_EQ(life.idle_left_us(3 * kS), 59 * kS);  // idle counts from the last grab
  EXPECT_EQ(life.step(still(), 61 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(still(), 62 * kS), VisitorAction::ended);
  EXPECT_EQ(life.end(), SculptureEnd::idle);
  EXPECT_TRUE(life.undoable());
  EXPECT_EQ(life.grace_left_us(64 * kS), 3 * kS);
  EXPECT_EQ(life.step(still(), 66 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(still(), 67 * kS), VisitorAction::archive);
  life.archived(true, 67 * kS);
  EXPECT_EQ(life.phase(), VisitorPhase::attract);
}

TEST(VisitorLifecycle, HandMotionKeepsTheSculptureAliveSmallDriftDoesNot) {
  VisitorLifecycle life(config());
  life.start(true, 0);
  VisitorInputs in = still();
  EXPECT_EQ(life.step(in, 0), VisitorAction::none);
  in.hand_m[0][0] += 0.01;  // 1 cm: below the threshold
  EXPECT_EQ(life.step(in, 30 * kS), VisitorAction::none);
  in.hand_m[0][0] += 0.05;  // 6 cm from the reference: motion
  EXPECT_EQ(life.step(in, 50 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(in, 109 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(in, 110 * kS), VisitorAction::ended);
}

TEST(VisitorLifecycle, ChordHeldForAMomentEndsTheChordAgainUndoes) {
  VisitorLifecycle life(config());
  life.start(true, 0);
  VisitorInputs chord = still();
  chord.chord_held = true;
  EXPECT_EQ(life.step(chord, kS), VisitorAction::none);
  EXPECT_EQ(life.step(chord, 2 * kS), VisitorAction::none);  // held 1 s: not yet
  EXPECT_EQ(life.step(chord, 2 * kS + kS / 2), VisitorAction::ended);
  EXPECT_EQ(life.end(), SculptureEnd::chord);
  // Still held: it acted once; it must be released before it acts again.
  EXPECT_EQ(life.step(chord, 4 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(still(), 4 * kS + 1), VisitorAction::none);
  EXPECT_EQ(life.step(chord, 5 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(chord, 6 * kS + kS / 2), VisitorAction::undone);
  EXPECT_EQ(life.phase(), VisitorPhase::sculpting);
}

TEST(VisitorLifecycle, CommandsAndAGrabInTheGraceGoBackToSculpting) {
  VisitorLifecycle life(config());
  life.start(false, 0);
  EXPECT_EQ(life.request_new(0), VisitorAction::refused);  // nothing to end
  EXPECT_EQ(life.request_undo(0), VisitorAction::refused);
  EXPECT_EQ(life.step(grabbing(), kS), VisitorAction::began);
  EXPECT_EQ(life.request_new(2 * kS), VisitorAction::ended);
  EXPECT_EQ(life.end(), SculptureEnd::command);
  EXPECT_EQ(life.request_undo(3 * kS), VisitorAction::undone);
  EXPECT_EQ(life.request_new(4 * kS), VisitorAction::ended);
  EXPECT_EQ(life.step(grabbing(), 5 * kS), VisitorAction::undone);  // the visitor goes on
}

TEST(VisitorLifecycle, AFailedArchiveIsRetriedAndNeverResets) {
  VisitorLifecycle life(config());
  life.start(true, 0);
  EXPECT_EQ(life.request_new(0), VisitorAction::ended);
  EXPECT_EQ(life.step(still(), 5 * kS), VisitorAction::archive);
  life.archived(false, 5 * kS);
  EXPECT_EQ(life.phase(), VisitorPhase::finished);
  EXPECT_TRUE(life.archive_pending());
  EXPECT_EQ(life.step(still(), 7 * kS), VisitorAction::none);
  EXPECT_EQ(life.step(still(), 8 * kS), VisitorAction::archive);
  life.archived(true, 8 * kS);
  EXPECT_EQ(life.phase(), VisitorPhase::attract);
}

// Random steps (time jumps, grabs, chord, hand jumps, tracking, commands, archive
// outcomes): the phase only moves along the diagram's edges with their action; an
// archive is asked only in finished, after the grace (or the retry) since it began,
// never while a stroke is open; an idle end comes idle_us after the last activity;
// every end is undone or archived exactly once before the next end.
RC_GTEST_PROP(VisitorLifecycleProperty, PhasesMoveOnlyAlongTheDiagram, ()) {
  const VisitorConfig c = config();
  VisitorLifecycle life(c);
  const bool has = *rc::gen::arbitrary<bool>();
  life.start(has, 0);
  ports::TimestampUs now = 0;
  ports::TimestampUs activity = 0;
  ports::TimestampUs finished_at = -1;
  ports::TimestampUs failed_at = -1;
  int open_ends = 0;
  VisitorInputs in = still();
  const int steps = *rc::gen::inRange(1, 400);
  for (int i = 0; i < steps; ++i) {
    now += *rc::gen::element<ports::TimestampUs>(1, kS / 10, kS, 7 * kS, 30 * kS);
    in.active = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    in.chord_held = *rc::gen::weightedElement<bool>({{3, false}, {1, true}});
    const bool jump = *rc::gen::weightedElement<bool>({{4, false}, {1, true}});
    if (jump) in.hand_m[1][2] += 0.5;
    const VisitorPhase before = life.phase();
    const int what = *rc::gen::inRange(0, 10);
    VisitorAction a = VisitorAction::none;
    if (what == 0) {
      a = life.request_new(now);
      RC_ASSERT((a == VisitorAction::ended) == (before == VisitorPhase::sculpting));
    } else if (what == 1) {
      a = life.request_undo(now);
      RC_ASSERT((a == VisitorAction::undone) == (before == VisitorPhase::finished));
    } else {
      a = life.step(in, now);
    }
    const VisitorPhase after = life.phase();
    RC_ASSERT(life.idle_left_us(now) <= c.idle_us);
    RC_ASSERT(life.grace_left_us(now) <= c.grace_us);
    switch (a) {
      case VisitorAction::began:
        RC_ASSERT(before == VisitorPhase::attract && after == VisitorPhase::sculpting);
        RC_ASSERT(in.active);
        break;
      case VisitorAction::ended:
        RC_ASSERT(before == VisitorPhase::sculpting && after == VisitorPhase::finished);
        if (life.end() == SculptureEnd::idle) {
          RC_ASSERT(!in.active && !jump);
          RC_ASSERT(now - activity >= c.idle_us);
        }
        ++open_ends;
        RC_ASSERT(open_ends == 1);
        finished_at = now;
        failed_at = -1;
        break;
      case VisitorAction::undone:
        RC_ASSERT(before == VisitorPhase::finished && after == VisitorPhase::sculpting);
        --open_ends;
        break;
      case VisitorAction::archive: {
        RC_ASSERT(before == VisitorPhase::finished && after == VisitorPhase::finished);
        RC_ASSERT(!in.active);
        const bool due =
            failed_at >= 0 ? now - failed_at >= c.retry_us : now - finished_at >= c.grace_us;
        RC_ASSERT(due);
        const bool ok = *rc::gen::arbitrary<bool>();
        life.archived(ok, now);
        if (ok) {
          RC_ASSERT(life.phase() == VisitorPhase::attract);
          --open_ends;
        } else {
          RC_ASSERT(life.phase() == VisitorPhase::finished);
          failed_at = now;
        }
        break;
      }
      case VisitorAction::refused:
      case VisitorAction::none:
        RC_ASSERT(before == after);
        break;
    }
    const bool stepped = what >= 2;
    if (life.phase() == VisitorPhase::sculpting &&
        ((stepped && (in.active || jump)) || a == VisitorAction::began ||
         a == VisitorAction::undone)) {
      activity = now;
    }
    RC_ASSERT(open_ends == (life.phase() == VisitorPhase::finished ? 1 : 0));
  }
}

}  // namespace
}  // namespace twister::session
