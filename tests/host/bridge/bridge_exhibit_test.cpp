// Issue 25 (label exhibit), the display's side without OpenGL: the replica keeps the
// station's visitor state and its newest notices (bounded); ExhibitModel's words for
// the visitor and the operator, attract mode and how long notices stay up; the keys.
#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

#include "exhibit_model.hpp"
#include "scene_replica.hpp"
#include "twister/input/interaction_machine.hpp"
#include "window_input.hpp"

namespace twister::bridge {
namespace {

HudInput connected(double now_s = 0.0) {
  HudInput in;
  in.link = LinkView::connected;
  in.ready = true;
  in.now_s = now_s;
  return in;
}

link::VisitorState visitor(link::VisitorPhase phase, std::uint8_t flags = 0, float idle = 0.0F,
                           float grace = 0.0F) {
  link::VisitorState v;
  v.phase = phase;
  v.flags = flags;
  v.visitor = 7;
  v.sculpture = 42;
  v.strokes = 3;
  v.idle_left_s = idle;
  v.grace_left_s = grace;
  return v;
}

void grab(SceneReplica& r, bool on) {
  link::Hands h;
  h.flags = link::kHandSample0 | link::kHandTracked0;
  h.buttons = on ? 1 : 0;  // hand 1's grab
  (void)r.apply(h);
}

TEST(ExhibitReplica, KeepsTheLatestVisitorState) {
  SceneReplica r;
  EXPECT_FALSE(r.has_visitor());
  (void)r.apply(visitor(link::VisitorPhase::attract));
  (void)r.apply(visitor(link::VisitorPhase::sculpting, link::kVisitorDiskFull, 30.0F));
  ASSERT_TRUE(r.has_visitor());
  EXPECT_EQ(r.visitor().phase, link::VisitorPhase::sculpting);
  EXPECT_EQ(r.visitor().flags, link::kVisitorDiskFull);
  EXPECT_FLOAT_EQ(r.visitor().idle_left_s, 30.0F);
  EXPECT_EQ(r.visitor().sculpture, 42u);
}

TEST(ExhibitReplica, KeepsTheNewestNoticesBoundedAndNumbered) {
  SceneReplica r;
  EXPECT_TRUE(r.notices().empty());
  for (int i = 0; i < 20; ++i)
    (void)r.apply(link::Notice{static_cast<link::NoticeCode>(1 + i % 9), 0});
  EXPECT_EQ(r.notices_received(), 20u);
  const auto kept = r.notices();
  ASSERT_EQ(kept.size(), kNoticeRing);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::uint64_t number = 20 - kNoticeRing + 1 + i;  // oldest first
    EXPECT_EQ(kept[i].number, number);
    EXPECT_EQ(kept[i].notice.code, static_cast<link::NoticeCode>(1 + (number - 1) % 9));
  }
}

// Property: whatever notices come, interleaved with other messages, the replica keeps
// exactly the newest min(n, kNoticeRing), oldest first, numbered 1..n.
RC_GTEST_PROP(ExhibitReplica, TheNoticeRingHoldsTheNewestInOrder, ()) {
  SceneReplica r;
  std::vector<link::NoticeCode> sent;
  const auto steps = *rc::gen::inRange<std::size_t>(0, 40);
  for (std::size_t i = 0; i < steps; ++i) {
    if (*rc::gen::inRange(0, 4) == 0) {
      (void)r.apply(visitor(link::VisitorPhase::sculpting));
      continue;
    }
    const auto code = static_cast<link::NoticeCode>(*rc::gen::inRange(1, 10));
    (void)r.apply(link::Notice{code, 0});
    sent.push_back(code);
  }
  const auto kept = r.notices();
  RC_ASSERT(r.notices_received() == sent.size());
  RC_ASSERT(kept.size() == std::min(sent.size(), kNoticeRing));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::size_t at = sent.size() - kept.size() + i;
    RC_ASSERT(kept[i].number == at + 1);
    RC_ASSERT(kept[i].notice.code == sent[at]);
  }
}

TEST(ExhibitWords, AttractInvitesUntilTheFirstGrab) {
  SceneReplica r;
  ExhibitModel m;
  (void)r.apply(visitor(link::VisitorPhase::attract));
  ExhibitText t = m.update(r, connected(), Audience::visitor);
  EXPECT_TRUE(t.attract);
  EXPECT_EQ(t.prompt, "Pick up the handles and squeeze to grab");
  grab(r, true);  // the first grab hands the display over before the phase changes
  t = m.update(r, connected(), Audience::visitor);
  EXPECT_FALSE(t.attract);
  EXPECT_NE(t.prompt, "Pick up the handles and squeeze to grab");
  grab(r, false);
  (void)r.apply(visitor(link::VisitorPhase::sculpting));
  EXPECT_FALSE(m.update(r, connected(), Audience::visitor).attract);
  // The operator's view turns too in attract mode, with no visitor words.
  (void)r.apply(visitor(link::VisitorPhase::attract));
  t = m.update(r, connected(), Audience::operator_hud);
  EXPECT_TRUE(t.attract);
  EXPECT_TRUE(t.prompt.empty());
}

TEST(ExhibitWords, TheStatesThatMatterToAVisitor) {
  SceneReplica r;
  ExhibitModel m;
  HudInput waiting;
  EXPECT_EQ(m.update(r, waiting, Audience::visitor).prompt, "One moment, please");
  // No exhibit on this station: the first stroke is invited all the same.
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt, "Grab with both hands");
  link::VisitorState fresh = visitor(link::VisitorPhase::sculpting);
  fresh.strokes = 0;
  (void)r.apply(fresh);
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt, "Grab with both hands");
  (void)r.apply(visitor(link::VisitorPhase::sculpting, 0, 40.0F));
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt, "");  // busy sculpting: quiet
  (void)r.apply(visitor(link::VisitorPhase::sculpting, 0, 9.2F));
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt,
            "Still there? This sculpture ends in 10 s");
  (void)r.apply(visitor(link::VisitorPhase::finished, link::kVisitorResetUndoable, 0.0F, 4.5F));
  ExhibitText t = m.update(r, connected(), Audience::visitor);
  EXPECT_EQ(t.prompt, "Your sculpture is saved");
  EXPECT_EQ(t.detail, "changed your mind? press U within 5 s to keep going");
  (void)r.apply(visitor(link::VisitorPhase::finished));
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).detail,
            "sculpture 42, 3 strokes: thank you!");
  (void)r.apply(visitor(link::VisitorPhase::finished, link::kVisitorArchiveFailed));
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt, "Thank you for sculpting!");
  link::StatusReport lost;
  lost.tracker_state = static_cast<std::uint8_t>(link::TrackerState::lost);
  (void)r.apply(lost);
  EXPECT_EQ(m.update(r, connected(), Audience::visitor).prompt, "Tracker lost, please wait");
  // The operator reads the technical HUD instead, with the visitor line.
  EXPECT_EQ(m.update(r, connected(), Audience::operator_hud).prompt, "");
  EXPECT_EQ(visitor_line(r),
            "visitor: finished, visitor 7, sculpture 42, 3 strokes, idle left 0 s, ARCHIVE FAILED");
}

TEST(ExhibitWords, EachNoticeShowsOnceForItsTimeWithItsReason) {
  SceneReplica r;
  ExhibitModel m;
  (void)r.apply(visitor(link::VisitorPhase::sculpting));
  (void)r.apply(link::Notice{link::NoticeCode::undo_refused, 0});
  ExhibitText t = m.update(r, connected(10.0), Audience::visitor);
  ASSERT_EQ(t.notices.size(), 1u);
  EXPECT_EQ(t.notices[0], "Nothing to undo");
  t = m.update(r, connected(11.0), Audience::operator_hud);
  ASSERT_EQ(t.notices.size(), 1u);  // the same notice, not taken again
  (void)r.apply(link::Notice{link::NoticeCode::disk_full, 0});
  t = m.update(r, connected(13.0), Audience::operator_hud);
  ASSERT_EQ(t.notices.size(), 1u);  // the first one's time is up
  EXPECT_EQ(t.notices[0], "DISK FULL: The archive is full: sculpting goes on");
  EXPECT_TRUE(
      m.update(r, connected(13.0 + ExhibitModel::kNoticeShowS), Audience::visitor).notices.empty());
  m.local_notice("Not connected to the station: the key did nothing", 20.0);
  EXPECT_EQ(m.update(r, connected(21.0), Audience::visitor).notices.size(), 1u);
  // Every code has its own sentence.
  for (std::uint8_t c = 1; c <= link::kLastNoticeCode; ++c) {
    const auto code = static_cast<link::NoticeCode>(c);
    EXPECT_NE(notice_sentence(code), notice_sentence(static_cast<link::NoticeCode>(0))) << int(c);
    for (std::uint8_t d = 1; d < c; ++d)
      EXPECT_NE(notice_sentence(code), notice_sentence(static_cast<link::NoticeCode>(d)));
  }
}

// The station's detail (the session's reason) says why: a stroke open, an untracked
// handle, hands together; with exhibit mode off too (no visitor state).
TEST(ExhibitWords, ARefusalsReasonChoosesItsWords) {
  SceneReplica r;
  ExhibitModel m;
  const auto reason = [](twister::input::Reason x) { return static_cast<std::uint8_t>(x); };
  (void)r.apply(link::Notice{link::NoticeCode::undo_refused, reason(twister::input::Reason::busy)});
  (void)r.apply(link::Notice{link::NoticeCode::nothing_to_act_on,
                             reason(twister::input::Reason::no_tracking)});
  (void)r.apply(link::Notice{link::NoticeCode::redo_refused,
                             reason(twister::input::Reason::nothing_to_redo)});
  const ExhibitText t = m.update(r, connected(5.0), Audience::visitor);
  EXPECT_EQ(t.notices,
            (std::vector<std::string>{"Undo waits until the stroke ends",
                                      "That handle is not tracked: bring it back in view",
                                      "Nothing to redo"}));
  EXPECT_EQ(notice_sentence(link::NoticeCode::nothing_to_act_on,
                            reason(twister::input::Reason::hands_too_close)),
            "Hands too close together to set the size");
  EXPECT_EQ(notice_sentence(link::NoticeCode::symmetry_changed, 1),
            notice_sentence(link::NoticeCode::symmetry_changed));
}

TEST(ExhibitWords, ANoticeSayingWhatThePromptSaysIsNotShownTwice) {
  SceneReplica r;
  ExhibitModel m;
  (void)r.apply(visitor(link::VisitorPhase::finished));
  (void)r.apply(link::Notice{link::NoticeCode::sculpture_archived, 0});
  const ExhibitText t = m.update(r, connected(), Audience::visitor);
  EXPECT_EQ(t.prompt, "Your sculpture is saved");
  EXPECT_TRUE(t.notices.empty());
}

TEST(ExhibitKeys, CommandKeysAndTheirHelp) {
  EXPECT_EQ(key_action(GLFW_KEY_N), KeyAction::new_sculpture);
  EXPECT_EQ(key_action(GLFW_KEY_U), KeyAction::undo_new_sculpture);
  EXPECT_EQ(key_action(GLFW_KEY_TAB), KeyAction::toggle_audience);
  const std::string help = key_help();
  for (const char* key : {"  Z ", "  Y ", "  M ", "  N ", "  U ", "  H ", "  Tab ", "  C "})
    EXPECT_NE(help.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace twister::bridge
