#include "twister/session/sculpt_session.hpp"

#include <gtest/gtest.h>

#include <array>
#include <glm/geometric.hpp>
#include <numbers>

#include "session_harness.hpp"

namespace twister::session {
namespace {

using namespace test_support;
constexpr double kPi = std::numbers::pi;

std::uint32_t nearest_vertex(const mesh::Mesh& m, glm::vec3 p) {
  std::uint32_t best = 0;
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    if (glm::distance(m.position(i), p) < glm::distance(m.position(best), p)) best = i;
  }
  return best;
}

TEST(SculptSession, GrabDragReleaseCommitsAndJournals) {
  Station s;
  const auto original = s.mesh.checksum();
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.hand(1, math::identity_frame({5, 5, 5}));
  (void)s.tick();
  s.button(kGrab0, true);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  EXPECT_TRUE(s.session->busy());
  s.hand(0, math::identity_frame({0, 0, 0.3}));
  (void)s.tick();
  const LiveWarp live = s.session->live();
  ASSERT_TRUE(live.active);
  EXPECT_EQ(live.hand_mask, 1);
  EXPECT_GT(live.plan->indices().size(), 0u);
  const std::uint32_t centre = nearest_vertex(s.mesh, {0, 0, 0});
  EXPECT_NEAR(s.session->live_positions().z[centre], 0.3f, 1e-5f);
  EXPECT_EQ(s.mesh.checksum(), original);  // nothing committed yet
  s.button(kGrab0, false);
  const SessionEvents done = s.tick();
  ASSERT_TRUE(has_event(done, SessionEventKind::committed));
  EXPECT_NEAR(s.mesh.position(centre).z, 0.3f, 1e-5f);
  EXPECT_NE(s.mesh.checksum(), original);
  EXPECT_FALSE(s.session->busy());
  EXPECT_EQ(s.session->next_sequence(), 1u);
  EXPECT_GT(s.storage.bytes().size(), journal::kMaxFileHeaderBytes);
  EXPECT_EQ(s.storage.synced_size(), s.storage.bytes().size());
}

TEST(SculptSession, UndoThenRedoIsBitIdentical) {
  Station s;
  const auto original = s.mesh.checksum();
  s.hand(0, math::identity_frame({0.2, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, z_turn({0.3, 0.1, 0.2}, 1.0));
  (void)s.tick();
  s.button(kGrab0, false);
  (void)s.tick();
  const auto warped = s.mesh.checksum();
  ASSERT_TRUE(s.session->undo().ok());
  EXPECT_EQ(s.mesh.checksum(), original);
  ASSERT_TRUE(s.session->redo().ok());
  EXPECT_EQ(s.mesh.checksum(), warped);
  EXPECT_EQ(s.session->redo().code(), StatusCode::failed_precondition);
}

TEST(SculptSession, UndoIsRefusedDuringAStroke) {
  Station s;
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  EXPECT_EQ(s.session->undo().code(), StatusCode::failed_precondition);
}

// Three frozen 120-degree twists make a full 360-degree twist: a vertex of weight
// 1/2 turns by 180 degrees, which no single stroke could do (a 360-degree hand turn
// is the identity and a screw angle is at most 180 degrees).
TEST(SculptSession, ThreeFrozen120DegreeStepsMakeA360DegreeTwist) {
  Station s;
  const std::uint32_t half = nearest_vertex(s.mesh, {0.5f, 0, 0});        // weight 0.5
  const std::uint32_t quarter = nearest_vertex(s.mesh, {0.6875f, 0, 0});  // ~0.25
  ASSERT_EQ(s.mesh.position(half), glm::vec3(0.5f, 0, 0));
  const glm::vec3 q0 = s.mesh.position(quarter);
  s.hand(1, z_turn({0, 0, 0}, 0));
  s.hand(0, math::identity_frame({5, 5, 5}));
  s.button(kGrab1, true);
  (void)s.tick();
  for (int step = 1; step <= 3; ++step) {
    for (int k = 1; k <= 4; ++k) {  // turn in small increments, as a hand would
      s.hand(1, z_turn({0, 0, 0}, (2 * kPi / 3) * (step - 1 + k / 4.0)));
      (void)s.tick();
    }
    if (step < 3) {
      s.button(kFreeze1, true);
      ASSERT_TRUE(has_event(s.tick(), SessionEventKind::committed));
      s.button(kFreeze1, false);
      (void)s.tick();
    }
  }
  s.button(kGrab1, false);
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::committed));
  EXPECT_EQ(s.session->next_sequence(), 3u);  // three chained records
  const glm::vec3 p = s.mesh.position(half);
  EXPECT_NEAR(p.x, -0.5f, 1e-4f);
  EXPECT_NEAR(p.y, 0.0f, 1e-4f);
  // Weight w turns by w * 360 degrees.
  const double w = std::pow(std::cos(kPi / 2 * q0.x), 2);
  const double angle = std::atan2(s.mesh.position(quarter).y, s.mesh.position(quarter).x);
  double expected = std::remainder(w * 2 * kPi, 2 * kPi);
  EXPECT_NEAR(angle, expected, 1e-4);
}

// One stroke takes the minimal screw: a 240-degree hand turn is a -120-degree screw.
// (TurnTracking::minimal, the paper's behaviour; the default now unwraps turns.)
TEST(SculptSession, ASingleStrokeIsLimitedTo180Degrees) {
  for (const double turn_deg : {170.0, 240.0}) {
    SculptSessionConfig minimal = test_config();
    minimal.turns.tracking = TurnTracking::minimal;
    Station s(33, minimal);
    const std::uint32_t half = nearest_vertex(s.mesh, {0.5f, 0, 0});
    s.hand(1, z_turn({0, 0, 0}, 0));
    s.hand(0, math::identity_frame({5, 5, 5}));
    s.button(kGrab1, true);
    (void)s.tick();
    for (int k = 1; k <= 8; ++k) {
      s.hand(1, z_turn({0, 0, 0}, turn_deg * kPi / 180 * k / 8));
      (void)s.tick();
    }
    EXPECT_LE(s.session->live().plan->screw(0).angle, kPi);
    s.button(kGrab1, false);
    (void)s.tick();
    const glm::vec3 p = s.mesh.position(half);
    const double expected = (turn_deg > 180 ? turn_deg - 360 : turn_deg) / 2 * kPi / 180;
    EXPECT_NEAR(std::atan2(p.y, p.x), expected, 1e-4) << turn_deg;
  }
}

TEST(SculptSession, LostTrackingHoldsThenResumes) {
  Station s;
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, math::identity_frame({0, 0, 0.2}));
  (void)s.tick();
  s.lose(0);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::tracking_lost));
  const std::uint32_t centre = nearest_vertex(s.mesh, {0, 0, 0});
  EXPECT_NEAR(s.session->live_positions().z[centre], 0.2f, 1e-5f);  // held
  s.hand(0, math::identity_frame({0, 0, 0.4}));
  EXPECT_TRUE(has_event(s.tick(50'000), SessionEventKind::tracking_resumed));
  s.button(kGrab0, false);
  (void)s.tick();
  EXPECT_NEAR(s.mesh.position(centre).z, 0.4f, 1e-5f);
}

TEST(SculptSession, LostTrackingTooLongCancelsAndLeavesTheModelUnchanged) {
  Station s;
  const auto original = s.mesh.checksum();
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, math::identity_frame({0, 0, 0.2}));
  (void)s.tick();
  s.lose(0);
  (void)s.tick();
  const SessionEvents e = s.tick(150'000);
  ASSERT_TRUE(has_event(e, SessionEventKind::cancelled));
  EXPECT_EQ(e.items()[0].stroke_end().reason, input::Reason::tracking_timeout);
  EXPECT_EQ(s.mesh.checksum(), original);
  EXPECT_FALSE(s.session->busy());
  EXPECT_EQ(s.session->next_sequence(), 0u);  // nothing journaled
}

TEST(SculptSession, TwoHandsTogetherAndSecondGrabAtSamePointRefused) {
  Station s;
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.hand(1, math::identity_frame({-0.5, 0, 0.001}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.button(kGrab1, true);
  const SessionEvents refused = s.tick();
  ASSERT_TRUE(has_event(refused, SessionEventKind::refused));
  EXPECT_EQ(refused.items()[0].reasoned().reason, input::Reason::same_point);
  s.button(kGrab1, false);
  (void)s.tick();
  s.hand(1, math::identity_frame({0.5, 0, 0}));
  s.button(kGrab1, true);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  EXPECT_EQ(s.session->live().hand_mask, 3);
  EXPECT_EQ(s.session->live().plan->hand_count(), 2u);
  s.hand(0, math::identity_frame({-0.5, 0, 0.2}));
  s.hand(1, math::identity_frame({0.5, 0, -0.2}));
  (void)s.tick();
  s.button(kGrab0, false);
  s.button(kGrab1, false);
  (void)s.tick();
  EXPECT_NEAR(s.mesh.position(nearest_vertex(s.mesh, {-0.5f, 0, 0})).z, 0.2f, 1e-4f);
  EXPECT_NEAR(s.mesh.position(nearest_vertex(s.mesh, {0.5f, 0, 0})).z, -0.2f, 1e-4f);
}

// Both hands letting go in the same step end with one two-hand commit: neither hand
// "continues" for no time into a second, motionless record.
TEST(SculptSession, ReleasingBothHandsTogetherIsOneCommit) {
  Station s;
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.hand(1, math::identity_frame({0.5, 0, 0}));
  s.button(kGrab0, true);
  s.button(kGrab1, true);
  (void)s.tick();
  s.hand(0, math::identity_frame({-0.5, 0, 0.2}));
  s.hand(1, math::identity_frame({0.5, 0, -0.2}));
  (void)s.tick();
  s.button(kGrab0, false);
  s.button(kGrab1, false);
  const SessionEvents done = s.tick();
  std::array<int, 2> commits{};
  std::uint32_t sequence = 99;
  for (const SessionEvent& e : done.items()) {
    if (e.kind != SessionEventKind::committed) continue;
    ++commits[e.hand];
    EXPECT_EQ(e.stroke_end().reason, input::Reason::released);
    if (sequence == 99) sequence = e.stroke_end().sequence;
    EXPECT_EQ(e.stroke_end().sequence, sequence);  // the same record for both hands
  }
  EXPECT_EQ(commits[0], 1);
  EXPECT_EQ(commits[1], 1);
  EXPECT_EQ(s.session->next_sequence(), 1u);  // exactly one journal record
  EXPECT_FALSE(s.session->busy());
}

TEST(SculptSession, MoveObjectRigidlyWhileTheOtherHandWarps) {
  Station s;
  s.hand(0, math::identity_frame({2, 0, 0}));
  s.hand(1, math::identity_frame({0, 0, 0}));
  s.button(kMove0, true);
  s.button(kGrab1, true);
  const SessionEvents begin = s.tick();
  EXPECT_TRUE(has_event(begin, SessionEventKind::move_begin));
  EXPECT_TRUE(has_event(begin, SessionEventKind::grab_begin));
  s.hand(0, math::identity_frame({2, 1, 0}));  // object follows: +1 in y
  (void)s.tick();
  EXPECT_NEAR(s.session->object_pose().origin.y, 1.0, 1e-12);
  s.button(kMove0, false);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::move_committed));
  // The warping hand stayed at the world origin: in the object frame it moved to
  // y = -1, so the grabbed vertex at the object origin follows it there.
  s.button(kGrab1, false);
  (void)s.tick();
  EXPECT_NEAR(s.mesh.position(nearest_vertex(s.mesh, {0, -1, 0})).y, -1.0f, 1e-4f);
  ASSERT_TRUE(s.session->undo().ok());  // the warp
  ASSERT_TRUE(s.session->undo().ok());  // the move
  EXPECT_EQ(s.session->object_pose().origin, glm::dvec3(0.0));
}

TEST(SculptSession, ManyObjectMovesKeepTheObjectFrameOrthonormal) {
  Station s(9);
  for (int k = 0; k < 500; ++k) {
    s.hand(0, z_turn({0.1 * (k % 7), 0.0, 0.0}, 0.0));
    s.button(kMove0, true);
    (void)s.tick();
    const math::Frame f = z_turn({0.1 * (k % 5), 0.2, 0.01 * k}, 0.37 + 0.01 * k);
    s.hand(0, math::frame_from_uv(f.origin, f.u, glm::normalize(f.v + glm::dvec3(0, 0, 0.3))));
    (void)s.tick();
    s.button(kMove0, false);
    ASSERT_TRUE(has_event(s.tick(), SessionEventKind::move_committed));
  }
  EXPECT_TRUE(math::is_orthonormal(s.session->object_pose(), 1e-12));
  EXPECT_EQ(s.session->next_sequence(), 500u);
}

TEST(SculptSession, RadiusGestureScalesTheNextStroke) {
  Station s;
  s.hand(0, math::identity_frame({-0.2, 0, 0}));
  s.hand(1, math::identity_frame({0.2, 0, 0}));
  s.button(kRadius0, true);
  s.button(kRadius1, true);
  (void)s.tick();
  s.hand(1, math::identity_frame({0.6, 0, 0}));  // distance 0.4 -> 0.8
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::radius_changed));
  EXPECT_NEAR(s.session->radius_m(), 2.0f, 1e-5f);
  s.button(kRadius0, false);
  s.button(kRadius1, false);
  s.button(kGrab0, true);
  (void)s.tick();
  EXPECT_DOUBLE_EQ(s.session->live().plan->radius(), 2.0);
}

}  // namespace
}  // namespace twister::session
