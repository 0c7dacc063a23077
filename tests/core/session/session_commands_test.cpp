// Undo, redo and the warp method at hand (issue "a session"): command roles on
// buttons and chords (hold freeze, press grab = undo), the session's command path for
// a display (submit), the events they give and the state snapshot; chords in the
// ButtonMap and ButtonFrontEnd. Label interaction.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "session_harness.hpp"
#include "twister/input/button_front_end.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session {
namespace {

using namespace test_support;

constexpr std::uint8_t kMethodLine = 6;  // hand 0: method_cycle

// The paper's lines plus: hold right freeze + press right grab = undo, hold right
// freeze + press right radius = redo, line 6 = method cycle of the left hand.
SculptSessionConfig command_config() {
  SculptSessionConfig c = test_config();
  const std::array<std::uint8_t, 2> undo{kFreeze1, kGrab1};
  const std::array<std::uint8_t, 2> redo{kFreeze1, kRadius1};
  EXPECT_TRUE(c.buttons.bind_chord(undo, 1, input::ButtonRole::undo).ok());
  EXPECT_TRUE(c.buttons.bind_chord(redo, 1, input::ButtonRole::redo).ok());
  EXPECT_TRUE(c.buttons.bind(kMethodLine, 0, input::ButtonRole::method_cycle).ok());
  c.debounce.line_count = 8;
  return c;
}

const SessionEvent* find(const SessionEvents& events, SessionEventKind kind) {
  for (const SessionEvent& e : events.items()) {
    if (e.kind == kind) return &e;
  }
  return nullptr;
}

void stroke(Station& s) {
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, z_turn({0.1, 0, 0.2}, 0.5));
  (void)s.tick();
  s.button(kGrab0, false);
  (void)s.tick();
}

// A chord: press `held`, then `trigger`, release both; the events of the trigger's step.
SessionEvents chord(Station& s, std::uint8_t held, std::uint8_t trigger) {
  s.button(held, true);
  EXPECT_EQ(s.tick().items().size(), 0u);  // freeze alone while idle does nothing
  s.button(trigger, true);
  const SessionEvents e = s.tick();
  s.button(trigger, false);
  s.button(held, false);
  EXPECT_EQ(s.tick().items().size(), 0u);  // releasing them does nothing either
  return e;
}

TEST(SessionCommands, UndoAndRedoFromChords) {
  Station s(33, command_config());
  s.hand(1, math::identity_frame({0.9, 0.9, 0}));
  const std::uint64_t original = s.mesh.checksum();
  stroke(s);
  const std::uint64_t sculpted = s.mesh.checksum();
  ASSERT_NE(sculpted, original);
  EXPECT_EQ(s.session->state().undo_depth, 1u);

  const SessionEvents undone = chord(s, kFreeze1, kGrab1);
  const SessionEvent* e = find(undone, SessionEventKind::undone);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->hand, 1);
  EXPECT_EQ(e->record().sequence, 1u);  // the undo record follows the stroke's
  EXPECT_EQ(find(undone, SessionEventKind::grab_begin), nullptr);  // the trigger is consumed
  EXPECT_EQ(s.mesh.checksum(), original);
  EXPECT_EQ(s.session->state().redo_depth, 1u);

  const SessionEvents redone = chord(s, kFreeze1, kRadius1);
  ASSERT_NE(find(redone, SessionEventKind::redone), nullptr);
  EXPECT_EQ(s.mesh.checksum(), sculpted);
  EXPECT_EQ(s.session->next_sequence(), 3u);  // stroke, undo, redo: journaled

  // Nothing more to redo: refused with the reason.
  const SessionEvents again = chord(s, kFreeze1, kRadius1);
  const SessionEvent* refused = find(again, SessionEventKind::command_refused);
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->command_refusal().reason, input::Reason::nothing_to_redo);
  EXPECT_EQ(refused->command_refusal().command, SessionCommandKind::redo);
}

// Grabbing first and then pressing freeze is a freeze, not an undo: the chord needs
// its held line down before the trigger.
TEST(SessionCommands, TheChordOrderMatters) {
  Station s(33, command_config());
  stroke(s);
  s.hand(1, z_turn({0.5, 0, 0}, 0));
  s.button(kGrab1, true);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  s.button(kFreeze1, true);
  const SessionEvents frozen = s.tick();
  EXPECT_TRUE(has_event(frozen, SessionEventKind::disengaged));
  EXPECT_FALSE(has_event(frozen, SessionEventKind::undone));
}

TEST(SessionCommands, UndoIsRefusedWhileAStrokeIsOpen) {
  Station s(33, command_config());
  stroke(s);
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.button(kGrab0, true);  // hand 0 grabs: the session is busy
  (void)s.tick();
  s.button(kFreeze1, true);
  (void)s.tick();
  s.button(kGrab1, true);
  const SessionEvents e = s.tick();
  const SessionEvent* refused = find(e, SessionEventKind::command_refused);
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->command_refusal().reason, input::Reason::busy);
  EXPECT_EQ(s.session->next_sequence(), 1u);
}

TEST(SessionCommands, MethodCycleButtonChangesTheMethodOfTheNextStroke) {
  Station s(33, command_config());
  EXPECT_EQ(s.session->state().method, math::WarpMethod::twister);
  s.button(kMethodLine, true);
  const SessionEvents e = s.tick();
  const SessionEvent* changed = find(e, SessionEventKind::method_changed);
  ASSERT_NE(changed, nullptr);
  EXPECT_EQ(changed->method().method, math::WarpMethod::rottran);
  s.button(kMethodLine, false);
  (void)s.tick();
  EXPECT_EQ(s.session->method(), math::WarpMethod::rottran);
  // During a stroke the method is locked (the open stroke keeps its own).
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  EXPECT_EQ(s.session->live().plan->method(), math::WarpMethod::rottran);
  s.button(kMethodLine, true);
  const SessionEvents busy = s.tick();
  ASSERT_NE(find(busy, SessionEventKind::command_refused), nullptr);
  EXPECT_EQ(find(busy, SessionEventKind::command_refused)->command_refusal().reason,
            input::Reason::busy);
  s.button(kMethodLine, false);
  s.button(kGrab0, false);
  (void)s.tick();
  journal::JournalReader reader(s.storage);
  ASSERT_TRUE(reader.open().ok());
  const auto r = reader.next();
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->stroke.method, static_cast<std::uint8_t>(math::WarpMethod::rottran));
}

// The command path a display uses: queued, run at the next step, events as for buttons.
TEST(SessionCommands, SubmittedCommandsRunAtTheNextStep) {
  Station s;
  stroke(s);
  const std::uint64_t sculpted = s.mesh.checksum();
  ASSERT_TRUE(s.session->submit({SessionCommandKind::undo}).ok());
  EXPECT_EQ(s.mesh.checksum(), sculpted);  // not before the step
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::undone));
  ASSERT_TRUE(s.session->submit({SessionCommandKind::redo}).ok());
  ASSERT_TRUE(
      s.session->submit({SessionCommandKind::set_method, 0, math::WarpMethod::scodef}).ok());
  ASSERT_TRUE(s.session->submit({SessionCommandKind::next_method}).ok());
  const SessionEvents e = s.tick();
  EXPECT_TRUE(has_event(e, SessionEventKind::redone));
  EXPECT_EQ(s.mesh.checksum(), sculpted);
  EXPECT_EQ(s.session->method(), math::WarpMethod::twister);  // scodef, then the next one
  EXPECT_EQ(s.session->submit({SessionCommandKind::undo, 2}).code(), StatusCode::invalid_argument);
  for (std::size_t i = 0; i < kMaxQueuedCommands; ++i) {
    ASSERT_TRUE(s.session->submit({SessionCommandKind::next_method}).ok());
  }
  EXPECT_EQ(s.session->submit({SessionCommandKind::undo}).code(), StatusCode::resource_exhausted);
  (void)s.tick();
  EXPECT_TRUE(s.session->submit({SessionCommandKind::undo}).ok());
}

// The radius gesture reports each change and, at its end, the radius it settled on;
// the state shows it; with the gesture switched off the radius buttons do nothing.
TEST(SessionCommands, RadiusGestureEventsAndState) {
  for (const bool enabled : {true, false}) {
    SculptSessionConfig c = test_config();
    c.interaction.initial_radius_m = 0.25f;
    c.interaction.radius_gesture = enabled;
    Station s(33, c);
    s.hand(0, math::identity_frame({-0.25, 0, 0}));
    s.hand(1, math::identity_frame({0.25, 0, 0}));
    s.button(kRadius0, true);
    s.button(kRadius1, true);
    (void)s.tick();
    EXPECT_EQ(s.session->state().radius_gesture_active, enabled);
    EXPECT_TRUE(s.session->state().hands[0].buttons.radius);
    s.hand(1, math::identity_frame({0.75, 0, 0}));  // distance 0.5 -> 1.0
    const SessionEvents grow = s.tick();
    EXPECT_EQ(has_event(grow, SessionEventKind::radius_changed), enabled);
    s.button(kRadius0, false);
    const SessionEvents done = s.tick();
    const SessionEvent* set = find(done, SessionEventKind::radius_set);
    EXPECT_EQ(set != nullptr, enabled);
    const float expected = enabled ? 0.5f : 0.25f;
    EXPECT_NEAR(s.session->state().radius_m, expected, 1e-6f);
    if (set != nullptr) {
      EXPECT_NEAR(set->radius().radius_m, 0.5, 1e-6);
    }
    EXPECT_EQ(s.session->state().radius_gesture_enabled, enabled);
  }
}

TEST(SessionCommands, StateShowsHandsClutchAndTurn) {
  Station s;
  s.hand(1, z_turn({0, 0, 0}, 0));
  s.button(kGrab1, true);
  (void)s.tick();
  s.hand(1, z_turn({0, 0, 0}, 0.5));
  (void)s.tick();
  SessionState st = s.session->state();
  EXPECT_TRUE(st.stroke_active);
  EXPECT_EQ(st.hands[1].state, input::HandState::dragging);
  EXPECT_TRUE(st.hands[1].in_stroke);
  EXPECT_TRUE(st.hands[1].engaged);
  EXPECT_TRUE(st.hands[1].tracked);
  EXPECT_TRUE(st.hands[1].buttons.grab);
  EXPECT_NEAR(st.hands[1].turn_rad, 0.5, 1e-9);
  EXPECT_NEAR(st.hands[1].turn_limit_rad, kDefaultTurnLimitRad, 1e-12);
  EXPECT_FALSE(st.hands[0].in_stroke);
  EXPECT_EQ(st.turn_tracking, TurnTracking::unwrapped);
  s.button(kFreeze1, true);
  (void)s.tick();
  st = s.session->state();
  EXPECT_FALSE(st.hands[1].engaged);
  EXPECT_EQ(st.chain_step, 1);
  EXPECT_EQ(st.next_sequence, 1u);
}

TEST(ButtonChords, BindingRules) {
  input::ButtonMap m;
  const std::array<std::uint8_t, 1> one{3};
  const std::array<std::uint8_t, 2> twice{3, 3};
  const std::array<std::uint8_t, 4> four{1, 2, 3, 4};
  const std::array<std::uint8_t, 2> far{3, 16};
  const std::array<std::uint8_t, 2> ok{5, 3};
  EXPECT_EQ(m.bind_chord(one, 0, input::ButtonRole::undo).code(), StatusCode::invalid_argument);
  EXPECT_EQ(m.bind_chord(twice, 0, input::ButtonRole::undo).code(), StatusCode::invalid_argument);
  EXPECT_EQ(m.bind_chord(four, 0, input::ButtonRole::undo).code(), StatusCode::invalid_argument);
  EXPECT_EQ(m.bind_chord(far, 0, input::ButtonRole::undo).code(), StatusCode::out_of_range);
  EXPECT_EQ(m.bind_chord(ok, 2, input::ButtonRole::undo).code(), StatusCode::out_of_range);
  EXPECT_EQ(m.bind_chord(ok, 0, input::ButtonRole::none).code(), StatusCode::invalid_argument);
  EXPECT_TRUE(m.bind_chord(ok, 1, input::ButtonRole::undo).ok());
  EXPECT_EQ(m.bind_chord(ok, 1, input::ButtonRole::redo).code(), StatusCode::invalid_argument);
  for (std::uint8_t i = 1; i < input::kMaxChords; ++i) {
    const std::array<std::uint8_t, 2> c{static_cast<std::uint8_t>(i + 6), 0};
    EXPECT_TRUE(m.bind_chord(c, 0, input::ButtonRole::redo).ok());
  }
  const std::array<std::uint8_t, 2> more{15, 1};
  EXPECT_EQ(m.bind_chord(more, 0, input::ButtonRole::redo).code(), StatusCode::resource_exhausted);
}

TEST(ButtonChords, TheMostSpecificChordWinsAndLevelsFollowThePress) {
  input::ButtonMap m = input::ButtonMap::paper_default();
  const std::array<std::uint8_t, 2> undo{5, 3};
  const std::array<std::uint8_t, 3> redo{4, 5, 3};
  const std::array<std::uint8_t, 2> move{1, 0};  // a level role on a chord
  ASSERT_TRUE(m.bind_chord(undo, 1, input::ButtonRole::undo).ok());
  ASSERT_TRUE(m.bind_chord(redo, 1, input::ButtonRole::redo).ok());
  ASSERT_TRUE(m.bind_chord(move, 1, input::ButtonRole::move_object).ok());
  EXPECT_EQ(m.resolve(3, 0).role, input::ButtonRole::grab);
  EXPECT_EQ(m.resolve(3, 1u << 5).role, input::ButtonRole::undo);
  EXPECT_EQ(m.resolve(3, (1u << 5) | (1u << 4)).role, input::ButtonRole::redo);

  input::ButtonDebouncerConfig d;
  for (auto& i : d.interval_us) i = 0;
  input::ButtonFrontEnd b(d, m);
  ASSERT_TRUE(b.feed({1, true, 0}).ok());  // left radius held ...
  b.poll(0);
  EXPECT_TRUE(b.hand(0).radius);
  ASSERT_TRUE(b.feed({0, true, 1}).ok());  // ... then left grab: hand 1 moves the object
  b.poll(1);
  EXPECT_FALSE(b.hand(0).grab);
  EXPECT_TRUE(b.hand(1).move_object);
  EXPECT_EQ(b.held_lines(), 0b11);
  ASSERT_TRUE(b.feed({1, false, 2}).ok());  // the held line goes first: the chord stays
  b.poll(2);
  EXPECT_TRUE(b.hand(1).move_object);
  ASSERT_TRUE(b.feed({0, false, 3}).ok());
  b.poll(3);
  EXPECT_FALSE(b.hand(1).move_object);
  EXPECT_FALSE(b.hand(0).grab);
  ASSERT_TRUE(b.feed({5, true, 4}).ok());
  ASSERT_TRUE(b.feed({3, true, 4}).ok());
  b.poll(4);  // one poll, lowest line first: 3 before 5 -> grab, then a freeze press
  EXPECT_TRUE(b.hand(1).grab);
  EXPECT_TRUE(b.commands().empty());
}

}  // namespace
}  // namespace twister::session
