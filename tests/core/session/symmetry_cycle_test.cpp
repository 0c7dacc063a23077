// Issue 26: the symmetry cycle. The symmetry_cycle chord (hold the right radius, press
// the right freeze in the paper's map) and SessionCommandKind::cycle_symmetry step the
// next strokes' group through SculptSessionConfig::symmetry_cycle (default: none and
// the configured group), refused while a stroke is open (like the method) and when the
// cycle has one group; each change is one symmetry_changed event.
#include "twister/session/symmetry_cycle.hpp"

#include <gtest/gtest.h>

#include <string>

#include "session_harness.hpp"

namespace twister::session {
namespace {

using math::SymmetryKind;
using math::SymmetrySpec;
using namespace test_support;

const SymmetrySpec kNone{};
const SymmetrySpec kX{SymmetryKind::mirrors, math::kMirrorX, 0, 0};
const SymmetrySpec kRot6{SymmetryKind::rotation, 0, 2, 6};

std::string label(const SymmetrySpec& s) {
  char text[math::kSymmetryLabelSize];
  math::symmetry_label(s, text);
  return text;
}

TEST(SymmetryCycle, NextWrapsAndStartsFromTheFirstWhenLost) {
  SymmetryCycle c;
  ASSERT_TRUE(c.push(kNone).ok());
  EXPECT_EQ(c.next(kNone).status().code(), StatusCode::failed_precondition);  // one group
  ASSERT_TRUE(c.push(kX).ok());
  ASSERT_TRUE(c.push(kRot6).ok());
  EXPECT_EQ(*c.next(kNone), kX);
  EXPECT_EQ(*c.next(kX), kRot6);
  EXPECT_EQ(*c.next(kRot6), kNone);
  EXPECT_EQ(*c.next(SymmetrySpec{SymmetryKind::mirrors, 2, 0, 0}), kNone);
  EXPECT_EQ(c.push(SymmetrySpec{SymmetryKind::rotation, 0, 2, 13}).code(),
            StatusCode::invalid_argument);
}

TEST(SymmetryCycle, DefaultIsNoneAndTheConfiguredGroup) {
  const SymmetryCycle d = SymmetryCycle{}.resolved(kRot6);
  ASSERT_EQ(d.count, 2u);
  EXPECT_EQ(d.groups[0], kNone);
  EXPECT_EQ(d.groups[1], kRot6);
  EXPECT_EQ(SymmetryCycle{}.resolved(kNone).count, 1u);
}

TEST(SymmetryCycle, LabelsAreTheConfigNames) {
  EXPECT_EQ(label(kNone), "none");
  EXPECT_EQ(label(kX), "x");
  EXPECT_EQ(label(SymmetrySpec{SymmetryKind::mirrors, 7, 0, 0}), "xyz");
  EXPECT_EQ(label(kRot6), "rot6 z");
  EXPECT_EQ(label(SymmetrySpec{SymmetryKind::rotation_mirror, 0, 1, 12}), "rot12m y");
  char tiny[3];
  EXPECT_EQ(math::symmetry_label(kRot6, tiny), 2u);  // truncated, terminated
  EXPECT_EQ(std::string(tiny), "ro");
}

SculptSessionConfig cycling_config() {
  SculptSessionConfig c = test_support::test_config();
  c.symmetry = kX;
  EXPECT_TRUE(c.symmetry_cycle.push(kNone).ok());
  EXPECT_TRUE(c.symmetry_cycle.push(kX).ok());
  EXPECT_TRUE(c.symmetry_cycle.push(kRot6).ok());
  return c;
}

const SessionEvent* find(const SessionEvents& e, SessionEventKind kind) {
  for (const SessionEvent& x : e.items()) {
    if (x.kind == kind) return &x;
  }
  return nullptr;
}

TEST(SymmetryCycleSession, CommandStepsTheNextStrokesGroup) {
  Station s(9, cycling_config());
  EXPECT_EQ(s.session->state().symmetry.next, kX);
  for (const SymmetrySpec& want : {kRot6, kNone, kX}) {
    ASSERT_TRUE(s.session->submit({SessionCommandKind::cycle_symmetry, 0}).ok());
    const SessionEvents e = s.tick();
    const SessionEvent* changed = find(e, SessionEventKind::symmetry_changed);
    ASSERT_NE(changed, nullptr);
    EXPECT_EQ(changed->symmetry().spec, want);
    EXPECT_EQ(static_cast<const SculptSession&>(*s.session).symmetry(), want);
    EXPECT_EQ(s.session->state().symmetry.next, want);
  }
}

TEST(SymmetryCycleSession, RefusedWhileAStrokeIsOpenAndWithOneGroup) {
  Station s(9, cycling_config());
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  ASSERT_TRUE(s.session->state().stroke_active);
  ASSERT_TRUE(s.session->submit({SessionCommandKind::cycle_symmetry, 0}).ok());
  SessionEvents e = s.tick();
  const SessionEvent* refused = find(e, SessionEventKind::command_refused);
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->command_refusal().command, SessionCommandKind::cycle_symmetry);
  EXPECT_EQ(refused->command_refusal().reason, input::Reason::busy);
  EXPECT_EQ(static_cast<const SculptSession&>(*s.session).symmetry(), kX);
  EXPECT_EQ(s.session->state().symmetry.stroke, kX);

  Station plain(9);  // symmetry none: the cycle is {none}
  ASSERT_TRUE(plain.session->submit({SessionCommandKind::cycle_symmetry, 0}).ok());
  e = plain.tick();
  refused = find(e, SessionEventKind::command_refused);
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->command_refusal().reason, input::Reason::not_available);
}

TEST(SymmetryCycleSession, PaperMapChordHoldRightRadiusPressRightFreeze) {
  Station s(9, cycling_config());
  s.button(kRadius1, true);  // right radius alone does nothing
  EXPECT_EQ(s.tick().items().size(), 0u);
  s.button(kFreeze1, true);  // the chord's trigger
  const SessionEvents e = s.tick();
  const SessionEvent* changed = find(e, SessionEventKind::symmetry_changed);
  ASSERT_NE(changed, nullptr);
  EXPECT_EQ(changed->hand, 1);
  EXPECT_EQ(changed->symmetry().spec, kRot6);
  s.button(kFreeze1, false);
  s.button(kRadius1, false);
  EXPECT_EQ(s.tick().items().size(), 0u);
}

}  // namespace
}  // namespace twister::session
