// Freeze as the paper's clutch (issue "a session"): pressing freeze commits and the
// hand disengages (the model does not move while it turns back), releasing it
// re-engages from the pose of that moment, so three 120-degree twists with the hand
// turned back in between make a 360-degree twist; the journal replays it exactly.
// Label interaction.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <vector>

#include "session_harness.hpp"
#include "twister/session/sculpt_session.hpp"

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

std::size_t count(const SessionEvents& events, SessionEventKind kind) {
  std::size_t n = 0;
  for (const SessionEvent& e : events.items()) n += e.kind == kind ? 1 : 0;
  return n;
}

// The live columns of the open stroke, where the plan moves vertices.
std::vector<float> live_snapshot(const SculptSession& s) {
  std::vector<float> out;
  const LiveWarp w = s.live();
  const math::ConstVertexColumns p = s.live_positions();
  for (const std::uint32_t i : w.plan->indices()) {
    out.push_back(p.x[i]);
    out.push_back(p.y[i]);
    out.push_back(p.z[i]);
  }
  return out;
}

// Replays `live`'s journal onto a fresh grid; the mesh checksum of the result.
std::uint64_t replayed_checksum(Station& live) {
  Station replayed(33, test_config(), false);
  journal::JournalReader reader(live.storage);
  EXPECT_TRUE(reader.open().ok());
  const auto n = replayed.session->replay(reader);
  EXPECT_TRUE(n.ok());
  EXPECT_EQ(reader.problem(), journal::TailProblem::none);
  return replayed.mesh.checksum();
}

// Turns hand 1 about z at the origin from `from` to `to` degrees in 10-degree steps.
void turn(Station& s, double from_deg, double to_deg) {
  const int n = static_cast<int>(std::lround(std::fabs(to_deg - from_deg) / 10.0));
  for (int k = 1; k <= n; ++k) {
    s.hand(1, z_turn({0, 0, 0}, (from_deg + (to_deg - from_deg) * k / n) * kPi / 180.0));
    (void)s.tick();
  }
}

TEST(Clutch, ThreeTwistsWithTheHandTurnedBackMakeA360DegreeTwist) {
  Station s;
  const std::uint32_t half = nearest_vertex(s.mesh, {0.5f, 0, 0});        // weight 0.5
  const std::uint32_t quarter = nearest_vertex(s.mesh, {0.6875f, 0, 0});  // ~0.25
  const glm::vec3 q0 = s.mesh.position(quarter);
  s.hand(1, z_turn({0, 0, 0}, 0));
  s.hand(0, math::identity_frame({5, 5, 5}));
  s.button(kGrab1, true);
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  for (int step = 1; step <= 3; ++step) {
    turn(s, 0, 120);
    if (step == 3) break;
    s.button(kFreeze1, true);
    const SessionEvents frozen = s.tick();
    ASSERT_EQ(count(frozen, SessionEventKind::committed), 1u);
    ASSERT_EQ(count(frozen, SessionEventKind::disengaged), 1u);
    EXPECT_FALSE(s.session->state().hands[1].engaged);
    // Disengaged: turning the hand back moves neither the model nor the live warp.
    const std::uint64_t model = s.mesh.checksum();
    const std::vector<float> shown = live_snapshot(*s.session);
    for (int k = 1; k <= 12; ++k) {
      s.hand(1, z_turn({0.01 * k, 0, 0.02 * k}, (120.0 - 10.0 * k) * kPi / 180.0));
      const SessionEvents e = s.tick();
      EXPECT_EQ(count(e, SessionEventKind::committed), 0u);
      EXPECT_EQ(s.mesh.checksum(), model);
      EXPECT_EQ(live_snapshot(*s.session), shown) << k;
    }
    s.hand(1, z_turn({0, 0, 0}, 0));  // a relaxed hand, back where it started
    (void)s.tick();
    EXPECT_EQ(s.mesh.checksum(), model);
    s.button(kFreeze1, false);
    const SessionEvents engaged = s.tick();
    EXPECT_EQ(count(engaged, SessionEventKind::engaged), 1u);
    EXPECT_EQ(count(engaged, SessionEventKind::committed), 0u);  // nothing moved meanwhile
    EXPECT_TRUE(s.session->state().hands[1].engaged);
    EXPECT_EQ(s.session->state().chain_step, step);
  }
  s.button(kGrab1, false);
  ASSERT_TRUE(has_event(s.tick(), SessionEventKind::committed));
  EXPECT_EQ(s.session->next_sequence(), 3u);  // three chained records
  const glm::vec3 p = s.mesh.position(half);
  EXPECT_NEAR(p.x, -0.5f, 1e-4f);  // weight 1/2 turned by 180 degrees
  EXPECT_NEAR(p.y, 0.0f, 1e-4f);
  const double w = std::pow(std::cos(kPi / 2 * q0.x), 2);
  const double angle = std::atan2(s.mesh.position(quarter).y, s.mesh.position(quarter).x);
  EXPECT_NEAR(angle, std::remainder(w * 2 * kPi, 2 * kPi), 1e-4);  // weight w: w * 360
  EXPECT_EQ(replayed_checksum(s), s.mesh.checksum());
}

// Releasing the grab while on the clutch ends the stroke without another record.
TEST(Clutch, ReleasingTheGrabOnTheClutchAddsNoRecord) {
  Station s;
  s.hand(1, z_turn({0, 0, 0}, 0));
  s.button(kGrab1, true);
  (void)s.tick();
  turn(s, 0, 60);
  s.button(kFreeze1, true);
  (void)s.tick();
  turn(s, 60, 0);
  s.button(kGrab1, false);
  const SessionEvents done = s.tick();
  ASSERT_EQ(count(done, SessionEventKind::committed), 1u);
  EXPECT_TRUE(done.items()[0].stroke_end().repeat);      // the freeze step was the commit
  EXPECT_EQ(done.items()[0].stroke_end().sequence, 0u);  // ... and this is its record
  EXPECT_EQ(done.items()[0].stroke_end().reason, input::Reason::released);
  EXPECT_EQ(s.session->next_sequence(), 1u);
  EXPECT_FALSE(s.session->busy());
  s.button(kFreeze1, false);
  EXPECT_EQ(s.tick().items().size(), 0u);
  EXPECT_EQ(replayed_checksum(s), s.mesh.checksum());
}

// On the clutch the hand may leave the tracked volume: no lost-tracking timeout.
TEST(Clutch, ADisengagedHandMayLoseTrackingWithoutCancelling) {
  Station s;  // lost_timeout 100 ms
  const std::uint32_t half = nearest_vertex(s.mesh, {0.5f, 0, 0});
  s.hand(1, z_turn({0, 0, 0}, 0));
  s.button(kGrab1, true);
  (void)s.tick();
  turn(s, 0, 90);
  s.button(kFreeze1, true);
  (void)s.tick();
  s.lose(1);
  for (int k = 0; k < 50; ++k) EXPECT_FALSE(has_event(s.tick(), SessionEventKind::cancelled));
  s.hand(1, z_turn({0, 0, 0}, 0));
  (void)s.tick();
  s.button(kFreeze1, false);
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::engaged));
  turn(s, 0, 90);
  s.button(kGrab1, false);
  (void)s.tick();
  EXPECT_EQ(s.session->next_sequence(), 2u);
  EXPECT_NEAR(s.mesh.position(half).y, 0.5f, 1e-4f);  // weight 1/2 of 180 degrees: +90
  EXPECT_EQ(replayed_checksum(s), s.mesh.checksum());
}

// Two hands: one on the clutch, the other warping; the other hand joining, leaving and
// the clutched hand re-engaging all replay exactly (a disengaged hand keeps its anchor).
TEST(Clutch, TheOtherHandWarpsWhileOneIsDisengagedAndTheJournalReplays) {
  Station s;
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.hand(1, z_turn({0.5, 0, 0}, 0));
  s.button(kGrab1, true);
  (void)s.tick();
  for (int k = 1; k <= 6; ++k) {
    s.hand(1, z_turn({0.5, 0, 0.01 * k}, 0.2 * k));
    (void)s.tick();
  }
  s.button(kFreeze1, true);
  (void)s.tick();
  s.button(kGrab0, true);  // joins while hand 1 is on the clutch
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::grab_begin));
  for (int k = 1; k <= 6; ++k) {
    s.hand(0, math::identity_frame({-0.5, 0, 0.03 * k}));
    s.hand(1, z_turn({0.7, 0.2, 0.3}, -0.1 * k));  // wherever: it does not warp
    (void)s.tick();
  }
  const std::uint32_t anchor = nearest_vertex(s.mesh, {0.5f, 0, 0});
  const math::ConstVertexColumns live = s.session->live_positions();
  const glm::vec3 before = {live.x[anchor], live.y[anchor], live.z[anchor]};
  EXPECT_NEAR(before.z, s.mesh.position(anchor).z, 1e-6f);  // hand 1's material stays
  s.button(kGrab0, false);  // hand 0 leaves: hand 1, still disengaged, goes on alone
  (void)s.tick();
  s.hand(1, z_turn({0.6, 0.1, 0.2}, 0));
  (void)s.tick();
  s.button(kFreeze1, false);  // re-engages in a segment built while it was disengaged
  EXPECT_TRUE(has_event(s.tick(), SessionEventKind::engaged));
  for (int k = 1; k <= 6; ++k) {
    s.hand(1, z_turn({0.6, 0.1, 0.2 + 0.02 * k}, 0.25 * k));
    (void)s.tick();
  }
  s.button(kGrab1, false);
  (void)s.tick();
  EXPECT_FALSE(s.session->busy());
  EXPECT_GE(s.session->next_sequence(), 4u);
  EXPECT_EQ(replayed_checksum(s), s.mesh.checksum());
}

// Pressing freeze on the clutch of a two-hand stroke commits both hands' work.
TEST(Clutch, FreezeInATwoHandStrokeCommitsBothHands) {
  Station s;
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.hand(1, z_turn({0.5, 0, 0}, 0));
  s.button(kGrab0, true);
  s.button(kGrab1, true);
  (void)s.tick();
  s.hand(0, math::identity_frame({-0.5, 0, 0.2}));
  s.hand(1, z_turn({0.5, 0, 0.1}, 0.5));
  (void)s.tick();
  const std::uint64_t before = s.mesh.checksum();
  s.button(kFreeze1, true);
  const SessionEvents frozen = s.tick();
  EXPECT_EQ(count(frozen, SessionEventKind::committed), 1u);
  EXPECT_NE(s.mesh.checksum(), before);
  // Hand 0 goes on warping while hand 1 is on the clutch; releasing freeze commits it.
  s.hand(0, math::identity_frame({-0.5, 0, 0.3}));
  s.hand(1, z_turn({0.4, 0, 0}, -1.0));
  (void)s.tick();
  s.button(kFreeze1, false);
  const SessionEvents engaged = s.tick();
  EXPECT_EQ(count(engaged, SessionEventKind::committed), 1u);
  EXPECT_EQ(count(engaged, SessionEventKind::engaged), 1u);
  s.button(kGrab0, false);
  s.button(kGrab1, false);
  (void)s.tick();
  EXPECT_EQ(replayed_checksum(s), s.mesh.checksum());
}

}  // namespace
}  // namespace twister::session
