// Journal replay of SculptSession: bit-identical on the same mesh, same strokes on
// a finer mesh, power loss at every byte of an append, chain checks.
#include <gtest/gtest.h>

#include <numbers>

#include "session_harness.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session {
namespace {

using namespace test_support;
constexpr double kPi = std::numbers::pi;

// A session exercising every record kind: one-hand stroke, freeze chain,
// two-hand stroke, object move, undo, redo.
void stroke_one_hand(Station& s, glm::dvec3 from, glm::dvec3 to, double turn) {
  s.hand(0, math::identity_frame(from));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, z_turn(0.5 * (from + to), 0.5 * turn));
  (void)s.tick();
  s.hand(0, z_turn(to, turn));
  (void)s.tick();
  s.button(kGrab0, false);
  (void)s.tick();
}

void freeze_chain(Station& s) {
  s.hand(1, z_turn({0.3, -0.2, 0}, 0));
  s.button(kGrab1, true);
  (void)s.tick();
  for (int step = 1; step <= 3; ++step) {
    s.hand(1, z_turn({0.3, -0.2, 0.05 * step}, 2 * kPi / 3 * step));
    (void)s.tick();
    s.button(kFreeze1, true);
    (void)s.tick();
    s.button(kFreeze1, false);
    (void)s.tick();
  }
  s.button(kGrab1, false);
  (void)s.tick();
}

void two_hands(Station& s) {
  s.hand(0, math::identity_frame({-0.4, 0.1, 0}));
  s.hand(1, math::identity_frame({0.4, 0.1, 0}));
  s.button(kGrab0, true);
  s.button(kGrab1, true);
  (void)s.tick();
  s.hand(0, z_turn({-0.4, 0.1, 0.2}, 0.5));
  s.hand(1, z_turn({0.4, 0.1, -0.2}, -0.5));
  (void)s.tick();
  s.button(kGrab0, false);  // hand 1 goes on alone: a new segment
  (void)s.tick();
  s.hand(1, z_turn({0.5, 0.2, -0.1}, -0.2));
  (void)s.tick();
  s.button(kGrab1, false);
  (void)s.tick();
}

void move_object(Station& s) {
  s.hand(0, math::identity_frame({1, 1, 1}));
  s.button(kMove0, true);
  (void)s.tick();
  s.hand(0, z_turn({1.2, 0.9, 1.1}, 0.3));
  (void)s.tick();
  s.button(kMove0, false);
  (void)s.tick();
}

void full_script(Station& s) {
  stroke_one_hand(s, {0, 0, 0}, {0.1, 0.05, 0.2}, 0.4);
  freeze_chain(s);
  two_hands(s);
  move_object(s);
  stroke_one_hand(s, {-0.3, 0.3, 0}, {-0.3, 0.3, -0.1}, -0.7);  // in the moved object frame
  ASSERT_TRUE(s.session->undo().ok());
  ASSERT_TRUE(s.session->undo().ok());
  ASSERT_TRUE(s.session->redo().ok());
  stroke_one_hand(s, {0.6, 0.6, 0}, {0.6, 0.7, 0.1}, 0.1);
}

struct Replayed {
  std::unique_ptr<Station> station;
  std::size_t records = 0;
  journal::TailProblem problem = journal::TailProblem::none;
};

// Replays `storage` into a fresh session on a fresh grid of `grid` x `grid`.
Replayed replay(TestStorage& storage, int grid = 33) {
  Replayed r;
  r.station = std::make_unique<Station>(grid, test_config(), false);
  journal::JournalReader reader(storage);
  EXPECT_TRUE(reader.open().ok());
  auto n = r.station->session->replay(reader);
  EXPECT_TRUE(n.ok()) << n.status().name();
  r.records = n.value_or(0);
  r.problem = reader.problem();
  EXPECT_TRUE(reader.truncate_tail().ok());
  return r;
}

TEST(SculptSessionReplay, SameMeshIsBitIdentical) {
  Station live;
  full_script(live);
  const std::uint32_t records = live.session->next_sequence();
  EXPECT_GE(records, 12u);
  const Replayed r = replay(live.storage);
  EXPECT_EQ(r.records, records);
  EXPECT_EQ(r.problem, journal::TailProblem::none);
  EXPECT_EQ(r.station->mesh.checksum(), live.mesh.checksum());
  EXPECT_EQ(r.station->session->object_pose().origin, live.session->object_pose().origin);
  EXPECT_EQ(r.station->session->object_pose().u, live.session->object_pose().u);
  EXPECT_EQ(r.station->session->replay_stats().undos, 2u);
  EXPECT_EQ(r.station->session->replay_stats().redos, 1u);
  EXPECT_EQ(r.station->session->replay_stats().moves, 1u);
  EXPECT_EQ(r.station->session->next_sequence(), records);
  // The replayed history is live: undo works on it like on the original.
  ASSERT_TRUE(live.session->undo().ok());
  ASSERT_TRUE(r.station->session->undo().ok());
  EXPECT_EQ(r.station->mesh.checksum(), live.mesh.checksum());
}

TEST(SculptSessionReplay, FinerMeshGetsTheSameStrokes) {
  Station coarse(17);  // spacing 1/8; the 33 x 33 grid holds every coarse vertex
  full_script(coarse);
  const Replayed fine = replay(coarse.storage, 33);
  EXPECT_EQ(fine.records, coarse.session->next_sequence());
  EXPECT_EQ(fine.station->mesh.vertex_count(), 33u * 33u);
  float worst = 0.0f;
  for (std::uint32_t j = 0; j < 17; ++j) {
    for (std::uint32_t i = 0; i < 17; ++i) {
      const glm::vec3 c = coarse.mesh.position(j * 17 + i);
      const glm::vec3 f = fine.station->mesh.position(2 * j * 33 + 2 * i);
      worst = std::max({worst, std::abs(c.x - f.x), std::abs(c.y - f.y), std::abs(c.z - f.z)});
    }
  }
  EXPECT_LT(worst, 1e-5f);
  EXPECT_GT(coarse.mesh.position(8 * 17 + 8).z, 0.01f);  // the strokes did something
}

// Cut the power at every byte of the last append: replay gives exactly the mesh of
// the last fully committed record, and the journal accepts new records afterwards.
void check_power_loss_at_every_byte(bool last_is_undo) {
  auto prefix = [](Station& s) {
    stroke_one_hand(s, {0, 0, 0}, {0.1, 0.05, 0.2}, 0.4);
    stroke_one_hand(s, {0.2, 0, 0}, {0.2, 0.1, 0.1}, -0.4);
  };
  auto last = [last_is_undo](Station& s) {
    if (last_is_undo) {
      (void)s.session->undo();
    } else {
      stroke_one_hand(s, {-0.2, 0, 0}, {-0.2, 0.1, -0.1}, 0.8);
    }
  };
  Station reference;
  prefix(reference);
  const auto committed = reference.mesh.checksum();
  const std::size_t before = reference.storage.bytes().size();
  last(reference);
  const auto full = reference.mesh.checksum();
  ASSERT_NE(committed, full);
  const std::size_t record_bytes = reference.storage.bytes().size() - before;

  for (std::size_t cut = 0; cut <= record_bytes; ++cut) {
    SCOPED_TRACE(cut);
    Station s;
    prefix(s);
    s.storage.cut_power_after(cut);
    last(s);
    EXPECT_EQ(s.storage.powered(), cut == record_bytes);
    s.storage.power_on();  // reboot
    const Replayed r = replay(s.storage);
    EXPECT_EQ(r.station->mesh.checksum(), cut == record_bytes ? full : committed);
    EXPECT_EQ(r.problem == journal::TailProblem::none, cut == 0 || cut == record_bytes);
    // After truncation the station carries on journaling where it stopped.
    journal::JournalWriter writer(s.storage);
    ASSERT_TRUE(writer.open().ok());
    journal::JournalRecord undo;
    undo.type = journal::RecordType::undo;
    undo.sequence = r.station->session->next_sequence();
    ASSERT_TRUE(writer.append(undo).ok());
    EXPECT_TRUE(replay(s.storage).problem == journal::TailProblem::none);
  }
}

TEST(SculptSessionReplay, PowerLossAtEveryByteOfAStrokeAppend) {
  check_power_loss_at_every_byte(false);
}
TEST(SculptSessionReplay, PowerLossAtEveryByteOfAnUndoAppend) {
  check_power_loss_at_every_byte(true);
}

TEST(SculptSessionReplay, FreezeStepWithoutItsChainIsRejected) {
  Station s(17, test_config(), false);
  journal::JournalRecord r;
  r.type = journal::RecordType::stroke;
  r.stroke.hand_mask = 1;
  r.stroke.chain_step = 1;
  r.stroke.radius_m = 1.0;
  EXPECT_EQ(s.session->apply_record(r).code(), StatusCode::data_loss);
  journal::JournalRecord undo;
  undo.type = journal::RecordType::undo;
  EXPECT_EQ(s.session->apply_record(undo).code(), StatusCode::data_loss);
}

// Issue 11 changed this: a stroke whose record is not durable is not committed.
TEST(SculptSessionReplay, JournalFailureMeansTheStrokeIsNotSavedAndNotApplied) {
  Station s;
  const auto original = s.mesh.checksum();
  s.storage.fail_next_sync();
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  s.hand(0, math::identity_frame({0, 0, 0.2}));
  (void)s.tick();
  s.button(kGrab0, false);
  const SessionEvents e = s.tick();
  EXPECT_TRUE(has_event(e, SessionEventKind::not_saved));
  EXPECT_FALSE(has_event(e, SessionEventKind::committed));
  EXPECT_EQ(s.mesh.checksum(), original);
  EXPECT_EQ(replay(s.storage).records, 0u);  // the failed record was cut off again
}

}  // namespace
}  // namespace twister::session
