#include "twister/input/interaction_machine.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

namespace twister::input {
namespace {

std::vector<ActionKind> kinds(const ActionList& list) {
  std::vector<ActionKind> out;
  for (const Action& a : list.items()) out.push_back(a.kind);
  return out;
}

InteractionInputs two_hands(glm::vec3 p0, glm::vec3 p1) {
  InteractionInputs in;
  in.hands[0].pose_valid = true;
  in.hands[0].position_m = p0;
  in.hands[1].pose_valid = true;
  in.hands[1].position_m = p1;
  return in;
}

TEST(InteractionMachine, GrabDragRelease) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  EXPECT_TRUE(m.step(in, 0).items().empty());
  in.hands[0].buttons.grab = true;
  EXPECT_EQ(kinds(m.step(in, 10)), std::vector{ActionKind::grab_begin});
  EXPECT_EQ(m.state(0), HandState::dragging);
  EXPECT_EQ(m.state_since_us(0), 10);
  in.hands[0].position_m = {0.1f, 0, 0};
  EXPECT_TRUE(m.step(in, 20).items().empty());
  in.hands[0].buttons.grab = false;
  const ActionList out = m.step(in, 30);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out.items()[0].kind, ActionKind::commit);
  EXPECT_EQ(out.items()[0].reason, Reason::released);
  EXPECT_EQ(m.state(0), HandState::idle);
}

TEST(InteractionMachine, HeldButtonDoesNotRegrab) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[0].pose_valid = false;
  in.hands[0].buttons.grab = true;
  const ActionList refused = m.step(in, 0);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused.items()[0].reason, Reason::no_tracking);
  in.hands[0].pose_valid = true;  // tracking back, button still held: no grab
  EXPECT_TRUE(m.step(in, 1).items().empty());
  EXPECT_EQ(m.state(0), HandState::idle);
}

TEST(InteractionMachine, TwoHandsIndependently) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[0].buttons.grab = true;
  in.hands[1].buttons.grab = true;
  const ActionList both = m.step(in, 0);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both.items()[0].hand, 0);
  EXPECT_EQ(both.items()[1].hand, 1);
  in.hands[1].buttons.grab = false;
  EXPECT_EQ(kinds(m.step(in, 1)), std::vector{ActionKind::commit});
  EXPECT_EQ(m.state(0), HandState::dragging);
}

TEST(InteractionMachine, SecondGrabAtTheSamePointIsRefused) {
  InteractionMachine m({});
  auto in = two_hands({0.5f, 0, 0}, {0.5f, 0.001f, 0});
  in.hands[0].buttons.grab = true;
  ASSERT_EQ(kinds(m.step(in, 0)), std::vector{ActionKind::grab_begin});
  in.hands[1].buttons.grab = true;
  const ActionList out = m.step(in, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out.items()[0].kind, ActionKind::refused);
  EXPECT_EQ(out.items()[0].reason, Reason::same_point);
  EXPECT_STREQ(reason_name(out.items()[0].reason), "same_point");
  EXPECT_EQ(m.state(1), HandState::idle);
}

TEST(InteractionMachine, LostTrackingResumesWithinTimeout) {
  InteractionConfig c;
  c.lost_timeout_us = 1000;
  InteractionMachine m(c);
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[0].buttons.grab = true;
  (void)m.step(in, 0);
  in.hands[0].pose_valid = false;
  EXPECT_EQ(kinds(m.step(in, 100)), std::vector{ActionKind::tracking_lost});
  EXPECT_TRUE(m.step(in, 1099).items().empty());
  in.hands[0].pose_valid = true;
  EXPECT_EQ(kinds(m.step(in, 1099)), std::vector{ActionKind::tracking_resumed});
  EXPECT_EQ(m.state(0), HandState::dragging);
}

TEST(InteractionMachine, LostTrackingCancelsAfterTimeout) {
  InteractionConfig c;
  c.lost_timeout_us = 1000;
  InteractionMachine m(c);
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[0].buttons.grab = true;
  (void)m.step(in, 0);
  in.hands[0].pose_valid = false;
  (void)m.step(in, 100);
  const ActionList out = m.step(in, 1100);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out.items()[0].kind, ActionKind::cancel);
  EXPECT_EQ(out.items()[0].reason, Reason::tracking_timeout);
  EXPECT_EQ(m.state(0), HandState::idle);
  in.hands[0].pose_valid = true;  // still held: no new grab
  EXPECT_TRUE(m.step(in, 1200).items().empty());
}

TEST(InteractionMachine, FreezeOnlyWhileDragging) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[1].buttons.freeze = true;
  EXPECT_TRUE(m.step(in, 0).items().empty());
  in.hands[1].buttons.freeze = false;
  in.hands[1].buttons.grab = true;
  (void)m.step(in, 1);
  in.hands[1].buttons.freeze = true;
  EXPECT_EQ(kinds(m.step(in, 2)), std::vector{ActionKind::freeze});
  EXPECT_TRUE(m.step(in, 3).items().empty());  // held: one freeze per press
}

TEST(InteractionMachine, MoveObjectWithOneHandWhileTheOtherWarps) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {1, 0, 0});
  in.hands[0].buttons.move_object = true;
  in.hands[1].buttons.grab = true;
  EXPECT_EQ(kinds(m.step(in, 0)), (std::vector{ActionKind::move_begin, ActionKind::grab_begin}));
  EXPECT_EQ(m.state(0), HandState::moving);
  in.hands[1].buttons.move_object = true;  // the object is busy
  const ActionList out = m.step(in, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out.items()[0].reason, Reason::hand_busy);
  in.hands[0].buttons.move_object = false;
  EXPECT_EQ(kinds(m.step(in, 2)), std::vector{ActionKind::move_commit});
}

TEST(InteractionMachine, RadiusFollowsHandDistanceClamped) {
  InteractionConfig c;
  c.initial_radius_m = 0.2f;
  c.radius_min_m = 0.1f;
  c.radius_max_m = 0.5f;
  InteractionMachine m(c);
  auto in = two_hands({0, 0, 0}, {0.4f, 0, 0});
  in.hands[0].buttons.radius = true;
  in.hands[1].buttons.radius = true;
  EXPECT_EQ(kinds(m.step(in, 0)), std::vector{ActionKind::radius_begin});
  in.hands[1].position_m = {0.6f, 0, 0};  // distance x1.5
  const ActionList grow = m.step(in, 1);
  ASSERT_EQ(grow.size(), 1u);
  EXPECT_EQ(grow.items()[0].kind, ActionKind::radius_change);
  EXPECT_NEAR(m.radius_m(), 0.3f, 1e-6f);
  in.hands[1].position_m = {4.0f, 0, 0};
  (void)m.step(in, 2);
  EXPECT_FLOAT_EQ(m.radius_m(), 0.5f);
  in.hands[1].position_m = {0.02f, 0, 0};
  (void)m.step(in, 3);
  EXPECT_FLOAT_EQ(m.radius_m(), 0.1f);
  in.hands[0].buttons.radius = false;
  EXPECT_EQ(kinds(m.step(in, 4)), std::vector{ActionKind::radius_end});
}

TEST(InteractionMachine, RadiusWithHandsTogetherIsRefused) {
  InteractionMachine m({});
  auto in = two_hands({0, 0, 0}, {0, 0, 0.001f});
  in.hands[0].buttons.radius = true;
  in.hands[1].buttons.radius = true;
  const ActionList out = m.step(in, 0);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out.items()[0].reason, Reason::hands_too_close);
  in.hands[1].position_m = {1, 0, 0};
  EXPECT_TRUE(m.step(in, 1).items().empty());
}

// Property: over random inputs the machine stays in a defined state, every grab (and
// move) ends in exactly one commit or cancel, the radius stays within its limits.
RC_GTEST_PROP(InteractionMachineProperty, EveryGrabEndsInExactlyOneCommitOrCancel, ()) {
  InteractionConfig c;
  c.lost_timeout_us = *rc::gen::inRange<ports::TimestampUs>(0, 5000);
  InteractionMachine m(c);
  const auto steps = *rc::gen::inRange(1, 400);
  std::array<bool, kHandCount> grab_open{};
  std::array<bool, kHandCount> move_open{};
  ports::TimestampUs now = 0;
  InteractionInputs in;
  for (int i = 0; i < steps; ++i) {
    for (auto& h : in.hands) {
      // Bias towards small changes so strokes last several steps.
      if (*rc::gen::inRange(0, 4) == 0) h.buttons.grab = !h.buttons.grab;
      if (*rc::gen::inRange(0, 6) == 0) h.buttons.move_object = !h.buttons.move_object;
      if (*rc::gen::inRange(0, 6) == 0) h.buttons.radius = !h.buttons.radius;
      if (*rc::gen::inRange(0, 6) == 0) h.buttons.freeze = !h.buttons.freeze;
      if (*rc::gen::inRange(0, 5) == 0) h.pose_valid = !h.pose_valid;
      h.position_m =
          glm::vec3(*rc::gen::inRange(-100, 100), *rc::gen::inRange(-100, 100), 0) * 0.01f;
    }
    now += *rc::gen::inRange<ports::TimestampUs>(0, 2000);
    const ActionList out = m.step(in, now);
    for (const Action& a : out.items()) {
      RC_ASSERT(a.hand < kHandCount);
      switch (a.kind) {
        case ActionKind::grab_begin:
          RC_ASSERT(!grab_open[a.hand]);
          grab_open[a.hand] = true;
          break;
        case ActionKind::commit:
        case ActionKind::cancel:
          RC_ASSERT(grab_open[a.hand]);
          grab_open[a.hand] = false;
          break;
        case ActionKind::freeze:
          RC_ASSERT(grab_open[a.hand]);
          break;
        case ActionKind::move_begin:
          RC_ASSERT(!move_open[a.hand]);
          RC_ASSERT(!move_open[1 - a.hand]);
          move_open[a.hand] = true;
          break;
        case ActionKind::move_commit:
        case ActionKind::move_cancel:
          RC_ASSERT(move_open[a.hand]);
          move_open[a.hand] = false;
          break;
        default:
          break;
      }
    }
    for (std::uint8_t h = 0; h < kHandCount; ++h) {
      const auto s = m.state(h);
      RC_ASSERT(static_cast<std::uint8_t>(s) < kHandStateCount);
      RC_ASSERT(grab_open[h] == (s == HandState::dragging || s == HandState::dragging_lost));
      RC_ASSERT(move_open[h] == (s == HandState::moving || s == HandState::moving_lost));
    }
    RC_ASSERT(m.radius_m() >= c.radius_min_m);
    RC_ASSERT(m.radius_m() <= c.radius_max_m);
  }
}

}  // namespace
}  // namespace twister::input
