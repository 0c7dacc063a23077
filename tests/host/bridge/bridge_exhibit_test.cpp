// Issue 25 (label exhibit), the display's side without OpenGL: the replica keeps the
// station's visitor state and its newest notices (bounded); ExhibitModel's words for
// the visitor and the operator, attract mode and how long notices stay up; the keys.
#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "attract_showcase.hpp"
#include "exhibit_model.hpp"
#include "scene_replica.hpp"
#include "showcase_archive.hpp"
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

// The messages a showcase logs (level, the format with its text arguments appended).
class CapturedLog final : public ports::LogSink {
 public:
  std::vector<std::pair<ports::LogLevel, std::string>> lines;

 private:
  bool do_enabled(ports::LogLevel) const override { return true; }
  void do_write(ports::LogLevel level, const char*, const char* format,
                std::span<const ports::LogArg> args) override {
    std::string line = format;
    for (const ports::LogArg& a : args) {
      if (a.kind == ports::LogArg::Kind::text) line += std::string(" | ") + a.s;
    }
    lines.emplace_back(level, line);
  }
};

// Attract mode's showcase over a station's archive (issue 25): the newest complete
// archives first, each for its time with its caption; a bad model skipped, logged and
// counted once; at most `models` held; new archives appear at the next listing.
TEST(AttractShowcase, ShowsTheNewestArchivesInTurnSkipsBadOnesAndRescans) {
  test::ShowcaseArchive archive("twister_showcase_test");
  const std::string a = archive.add("20261127T101500", 7, 0.03F, 0.2F, 3);
  const std::string b = archive.add("20261127T113000", 8, 0.2F, 0.03F, 1);
  const std::string bad = archive.add_bad("20261127T120000", 9);
  std::filesystem::create_directories(archive.dir / ".tmp-5c000010-123");  // being written
  std::ofstream(archive.dir / "notes.txt") << "not an archive";
  CapturedLog log;
  ShowcaseOptions o;
  o.dir = archive.dir.string();
  o.models = 2;
  o.seconds_each = 5.0;
  o.rescan_s = 20.0;
  AttractShowcase showcase(o, log);
  showcase.begin(100.0);
  const ShowcaseModel* first = showcase.at(100.0);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->name, b);  // the newest readable one
  EXPECT_EQ(first->caption, "Sculpture 8 \u00b7 1 stroke");
  EXPECT_GT(first->mesh.triangle_count(), 100u);
  ASSERT_NE(showcase.at(105.0), nullptr);
  EXPECT_EQ(showcase.at(105.0)->name, a);
  EXPECT_EQ(showcase.at(105.0)->caption, "Sculpture 7 \u00b7 3 strokes");
  EXPECT_EQ(showcase.at(110.0)->name, b);
  EXPECT_EQ(showcase.counters().skipped, 1u);
  EXPECT_EQ(showcase.counters().loaded, 2u);
  ASSERT_EQ(log.lines.size(), 2u);
  EXPECT_EQ(log.lines[0].first, ports::LogLevel::warning);
  EXPECT_NE(log.lines[0].second.find(bad), std::string::npos);
  EXPECT_NE(log.lines[0].second.find("model.glb"), std::string::npos);
  EXPECT_NE(log.lines[1].second.find("showing"), std::string::npos);
  // A new visitor's sculpture: it appears at the next listing, the oldest goes (two held),
  // the bad one is not read again.
  const std::string c = archive.add("20261127T130000", 10, 0.1F, 0.1F, 5);
  EXPECT_EQ(showcase.at(115.0)->name, a);  // not listed yet
  showcase.begin(121.0);
  EXPECT_EQ(showcase.at(121.0)->name, c);
  EXPECT_EQ(showcase.models().size(), 2u);
  EXPECT_EQ(showcase.models()[1].name, b);
  EXPECT_EQ(showcase.counters().skipped, 1u);
  EXPECT_EQ(showcase.counters().loaded, 3u);
  EXPECT_EQ(showcase.counters().scans, 2u);
  EXPECT_EQ(log.lines.size(), 2u);
}

TEST(AttractShowcase, NoArchiveFallsBackToTheStationsModelAndSaysSoOnce) {
  CapturedLog log;
  ShowcaseOptions o;
  o.dir = "/nonexistent/twister/archive";
  o.rescan_s = 1.0;
  AttractShowcase showcase(o, log);
  showcase.begin(0.0);
  EXPECT_EQ(showcase.at(0.0), nullptr);
  EXPECT_EQ(showcase.at(5.0), nullptr);  // listed again: still nothing, not said again
  EXPECT_EQ(showcase.counters().scans, 2u);
  ASSERT_EQ(log.lines.size(), 1u);
  EXPECT_NE(log.lines[0].second.find("/nonexistent/twister/archive"), std::string::npos);
  EXPECT_NE(log.lines[0].second.find("station's model"), std::string::npos);
  // Only bad files: the same.
  test::ShowcaseArchive archive("twister_showcase_bad_test");
  archive.add_bad("20261127T120000", 1);
  CapturedLog log2;
  o.dir = archive.dir.string();
  AttractShowcase bad(o, log2);
  bad.begin(0.0);
  EXPECT_EQ(bad.at(0.0), nullptr);
  EXPECT_EQ(bad.counters().skipped, 1u);
  EXPECT_EQ(log2.lines.size(), 2u);  // the bad file, then the fall-back
}

TEST(AttractShowcase, NamesCaptionsAndTheUprightPlacement) {
  EXPECT_TRUE(archive_name("20261127T101500Z-v0007-5c0000a7"));
  EXPECT_FALSE(archive_name(".tmp-5c0000a7-123"));
  EXPECT_FALSE(archive_name("20261127T101500Z-v0007-5c0000a"));
  EXPECT_FALSE(archive_name("20261127X101500Z-v0007-5c0000a7"));
  EXPECT_EQ(showcase_caption("20261127T101500Z-v0012-5c0000a7", 4),
            "Sculpture 12 \u00b7 4 strokes");
  EXPECT_EQ(showcase_caption("20261127T101500Z-v0012-5c0000a7", -1), "Sculpture 12");
  // A column along +Y (glTF's up), placed with up -Z at (1, 2, 3) with radius 0.5.
  MeshData m;
  m.x = {-0.1F, 0.1F, 0.0F, 0.0F};
  m.y = {-1.0F, -1.0F, 1.0F, 1.0F};
  m.z = {0.0F, 0.0F, 0.1F, -0.1F};
  m.indices = {0, 1, 2, 0, 2, 3};
  const MeshData p = place_upright(m, glm::vec3(0.0F, 0.0F, -1.0F), glm::vec3(1, 2, 3), 0.5F);
  glm::vec3 lo(1e9F), hi(-1e9F);
  for (std::size_t i = 0; i < p.vertex_count(); ++i) {
    lo = glm::min(lo, glm::vec3(p.x[i], p.y[i], p.z[i]));
    hi = glm::max(hi, glm::vec3(p.x[i], p.y[i], p.z[i]));
  }
  EXPECT_NEAR(0.5F * (lo.x + hi.x), 1.0F, 1e-5F);
  EXPECT_NEAR(0.5F * (lo.y + hi.y), 2.0F, 1e-5F);
  EXPECT_NEAR(0.5F * (lo.z + hi.z), 3.0F, 1e-5F);
  EXPECT_NEAR(0.5F * glm::length(hi - lo), 0.5F, 1e-5F);
  EXPECT_GT(hi.z - lo.z, 4.0F * (hi.x - lo.x));  // the column's length is along the up axis
  EXPECT_LT(p.z[2], p.z[0]);                     // its top (+Y) toward -Z, the world's up
  EXPECT_EQ(p.indices, m.indices);
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
