#include "twister/session/undo_history.hpp"

#include <gtest/gtest.h>

namespace twister::session {
namespace {

void commit(UndoHistory& h, mesh::Mesh& m, std::uint32_t i, glm::vec3 p) {
  h.begin_entry();
  ASSERT_TRUE(h.record(i, m.position(i), p).ok());
  m.set_position(i, p);
  ASSERT_TRUE(h.end_entry().ok());
}

TEST(UndoHistory, UndoRedoRestoreExactPositions) {
  mesh::MeshWithStorage<4, 1> m;
  for (int i = 0; i < 4; ++i) (void)m.add_vertex({float(i), 0, 0});
  const auto original = m.checksum();
  UndoHistoryWithStorage<16, 4> h;
  commit(h, m, 1, {0.1f, 0.2f, 0.3f});
  commit(h, m, 1, {0.7f, 0.2f, 0.3f});
  const auto after = m.checksum();
  ASSERT_TRUE(h.undo(m).ok());
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_EQ(m.checksum(), original);
  EXPECT_EQ(h.undo(m).status().code(), StatusCode::failed_precondition);
  ASSERT_TRUE(h.redo(m).ok());
  ASSERT_TRUE(h.redo(m).ok());
  EXPECT_EQ(m.checksum(), after);
  EXPECT_EQ(h.redo(m).status().code(), StatusCode::failed_precondition);
}

TEST(UndoHistory, NewCommitDropsRedo) {
  mesh::MeshWithStorage<2, 1> m;
  (void)m.add_vertex({0, 0, 0});
  UndoHistoryWithStorage<16, 4> h;
  commit(h, m, 0, {1, 0, 0});
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_TRUE(h.can_redo());
  commit(h, m, 0, {2, 0, 0});
  EXPECT_FALSE(h.can_redo());
  EXPECT_EQ(h.undo_depth(), 1u);
}

TEST(UndoHistory, OldestIsDroppedWhenEntriesOrChangesRunOut) {
  mesh::MeshWithStorage<8, 1> m;
  for (int i = 0; i < 8; ++i) (void)m.add_vertex({0, 0, 0});
  UndoHistoryWithStorage<4, 3> h;
  for (int k = 1; k <= 5; ++k) commit(h, m, 0, {float(k), 0, 0});
  EXPECT_EQ(h.undo_depth(), 3u);  // entry slots
  EXPECT_EQ(h.dropped_entries(), 2u);
  // A 3-vertex entry needs the change memory of older ones.
  h.begin_entry();
  for (std::uint32_t i = 1; i <= 3; ++i) ASSERT_TRUE(h.record(i, m.position(i), {9, 9, 9}).ok());
  for (std::uint32_t i = 1; i <= 3; ++i) m.set_position(i, {9, 9, 9});
  ASSERT_TRUE(h.end_entry().ok());
  EXPECT_EQ(h.undo_depth(), 2u);
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_EQ(m.position(2), glm::vec3(0, 0, 0));
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_EQ(m.position(0), glm::vec3(4, 0, 0));
  EXPECT_FALSE(h.can_undo());
}

TEST(UndoHistory, EntryLargerThanMemoryIsNotKept) {
  mesh::MeshWithStorage<8, 1> m;
  for (int i = 0; i < 8; ++i) (void)m.add_vertex({0, 0, 0});
  UndoHistoryWithStorage<4, 3> h;
  commit(h, m, 0, {1, 0, 0});
  h.begin_entry();
  Status last;
  for (std::uint32_t i = 0; i < 6; ++i) last = h.record(i, {}, {1, 1, 1});
  EXPECT_EQ(last.code(), StatusCode::resource_exhausted);
  EXPECT_EQ(h.end_entry().code(), StatusCode::resource_exhausted);
  EXPECT_FALSE(h.can_undo());
  EXPECT_FALSE(h.can_redo());
}

TEST(UndoHistory, ObjectPoseTravelsWithTheEntry) {
  mesh::MeshWithStorage<2, 1> m;
  UndoHistoryWithStorage<4, 3> h;
  const math::Frame before = math::identity_frame({1, 2, 3});
  const math::Frame after = math::identity_frame({4, 5, 6});
  h.begin_entry();
  h.record_object(before, after);
  ASSERT_TRUE(h.end_entry().ok());
  auto u = h.undo(m);
  ASSERT_TRUE(u.ok());
  EXPECT_TRUE(u->object_move);
  EXPECT_EQ(u->object_pose.origin, before.origin);
  auto r = h.redo(m);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->object_pose.origin, after.origin);
}

}  // namespace
}  // namespace twister::session
