// Checkpoints of refined sessions (format version 2): a session whose commits refined
// the mesh and whose history holds their topology (one of them undone) restores into a
// fresh session on the same start mesh bit for bit (counts, positions, triangles, every
// history entry, vertex change and triangle change), and undo, redo and new refined
// strokes go on identically; the bytes do not depend on the write budget; any damaged
// byte or cut is refused, and so is every structural edit that keeps the CRC right
// (triangle indices, topology ranges, the count chain, version 1), without touching the
// session; a checkpoint for another mesh capacity is refused.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint_harness.hpp"
#include "core/session/refine_harness.hpp"

namespace twister::checkpoint {
namespace {

using namespace test_support;

constexpr std::size_t kSpare = 4000;
constexpr double kThreshold = 0.01;

// A one-hand stroke of hand 0: grabs at `from`, drags to `to` turning by `turn_rad`.
void drag(RefineStation& s, glm::dvec3 from, glm::dvec3 to, double turn_rad) {
  s.hand(0, math::identity_frame(from));
  s.button(kGrab0, true);
  (void)s.tick();
  for (int k = 1; k <= 4; ++k) {
    s.hand(0, z_turn(from + (to - from) * (k / 4.0), turn_rad * k / 4.0));
    (void)s.tick();
  }
  s.button(kGrab0, false);
  (void)s.tick();
}

// An object move with hand 0 (an entry without topology).
void move_object(RefineStation& s) {
  s.hand(0, math::identity_frame({1, 1, 1}));
  s.button(kMove0, true);
  (void)s.tick();
  s.hand(0, z_turn({1.1, 0.9, 1.2}, 0.4));
  (void)s.tick();
  s.button(kMove0, false);
  (void)s.tick();
}

// Three refined strokes and a move, the last stroke undone (its topology stays in the
// history, redoable).
std::unique_ptr<RefineStation> refined_session(std::size_t spare, double threshold) {
  auto s = std::make_unique<RefineStation>(3, spare, refine_config(threshold));
  (void)twist_box(*s, 2.0);
  drag(*s, {0.5, 0.0, 0.0}, {0.6, 0.05, 0.1}, 0.8);
  move_object(*s);
  (void)twist_box(*s, -1.2);
  EXPECT_TRUE(s->session->undo().ok());
  return s;
}

bool same_normals(const session::SculptSession& a, const session::SculptSession& b) {
  const mesh::NormalColumns na = a.normals();
  const mesh::NormalColumns nb = b.normals();
  const std::size_t n = na.x.size();
  return n == nb.x.size() && n > 0 &&
         std::memcmp(na.x.data(), nb.x.data(), n * sizeof(float)) == 0 &&
         std::memcmp(na.y.data(), nb.y.data(), n * sizeof(float)) == 0 &&
         std::memcmp(na.z.data(), nb.z.data(), n * sizeof(float)) == 0;
}

TEST(RefineCheckpoint, RefinedSessionRestoresBitIdenticallyAndUndoRedoGoOnTheSame) {
  auto live = refined_session(kSpare, kThreshold);
  const session::UndoHistory& history = live->session->history();
  ASSERT_EQ(topology_count(history), 3u);
  ASSERT_TRUE(history.entries()[2].object_move);
  ASSERT_EQ(history.redo_depth(), 1u);
  ASSERT_GT(live->mesh().vertex_count(), meshio::box_vertices(3));
  const Bytes bytes = checkpoint_of(*live, 0);
  const CheckpointHeader h = header_of(bytes);
  EXPECT_EQ(h.vertex_count, live->mesh().vertex_count());
  EXPECT_EQ(h.triangle_count, live->mesh().triangle_count());
  EXPECT_EQ(h.used_triangle_changes, history.triangle_changes().size());
  EXPECT_GT(h.used_triangle_changes, 0u);
  std::printf("refined checkpoint: %zu bytes, %u vertices, %u triangles, %llu triangle changes\n",
              bytes.size(), h.vertex_count, h.triangle_count,
              static_cast<unsigned long long>(h.used_triangle_changes));

  auto restored = std::make_unique<RefineStation>(3, kSpare, refine_config(kThreshold), false);
  ASSERT_TRUE(restore_bytes(bytes, *restored).ok());
  EXPECT_TRUE(same_mesh(live->mesh(), restored->mesh()));
  EXPECT_TRUE(same_history(history, restored->session->history()));
  EXPECT_TRUE(same_session(*live, *restored));
  EXPECT_TRUE(same_normals(*live->session, *restored->session));

  // Redo the undone refinement, undo everything, redo everything: step for step equal.
  const std::vector<bool> script{true, false, false, false, false, true, true, true, true};
  for (std::size_t i = 0; i < script.size(); ++i) {
    SCOPED_TRACE(i);
    const Status a = script[i] ? live->session->redo() : live->session->undo();
    const Status b = script[i] ? restored->session->redo() : restored->session->undo();
    EXPECT_EQ(a.code(), b.code());
    EXPECT_TRUE(same_session(*live, *restored));
    EXPECT_TRUE(same_normals(*live->session, *restored->session));
  }
  EXPECT_FALSE(live->session->redo().ok());
  // A new refined stroke on both: the same refinement.
  const session::SessionEvents ea = twist_box(*live, 1.5);
  const session::SessionEvents eb = twist_box(*restored, 1.5);
  ASSERT_NE(find_event(ea, session::SessionEventKind::refined), nullptr);
  ASSERT_NE(find_event(eb, session::SessionEventKind::refined), nullptr);
  EXPECT_TRUE(same_session(*live, *restored));
}

TEST(RefineCheckpoint, TheBytesDoNotDependOnTheWriteBudget) {
  auto live = refined_session(kSpare, kThreshold);
  const Bytes whole = checkpoint_of(*live, 5);
  EXPECT_EQ(checkpoint_of(*live, 5, 1), whole);
  EXPECT_EQ(checkpoint_of(*live, 5, 5000), whole);
  EXPECT_EQ(whole.size(), checkpoint_bytes(header_of(whole)));
}

TEST(RefineCheckpoint, EveryDamagedByteOrCutIsRefusedWithoutTouchingTheSession) {
  auto live = refined_session(300, 0.03);
  const Bytes good = checkpoint_of(*live, 0);
  auto target = std::make_unique<RefineStation>(3, 300, refine_config(0.03), false);
  auto untouched = std::make_unique<RefineStation>(3, 300, refine_config(0.03), false);
  ASSERT_TRUE(verify_bytes(good, *target).ok());
  const std::size_t step = good.size() / 4000 + 1;
  std::size_t refused = 0;
  for (std::size_t i = 0; i < good.size(); i += (i < kCheckpointHeaderBytes ? 1 : step)) {
    Bytes bad = good;
    bad[i] ^= std::byte{0x20};
    const Status s = verify_bytes(bad, *target);
    EXPECT_EQ(s.code(), StatusCode::data_loss) << i;
    refused += s.ok() ? 0 : 1;
  }
  for (const std::size_t cut :
       {good.size() - 1, good.size() / 2, kCheckpointHeaderBytes, std::size_t{3}}) {
    EXPECT_EQ(
        verify_bytes(Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut)), *target)
            .code(),
        StatusCode::data_loss)
        << cut;
  }
  EXPECT_TRUE(same_session(*target, *untouched));
  std::printf("%zu damaged copies of a %zu-byte refined checkpoint refused\n", refused,
              good.size());
}

// An edit of `good` (the CRC made right again) that must be refused.
struct Edit {
  std::string what;
  std::function<void(Bytes&, const CheckpointHeader&, const CheckpointLayout&)> apply;
};

// The first refined entry and the undone (last) one.
std::size_t entry_at(const CheckpointLayout& l, std::size_t i) {
  return l.entries + i * kCheckpointEntryBytes;
}

std::vector<Edit> structural_edits(const session::UndoHistory& history) {
  const session::UndoEntry last = history.entries().back();
  const std::size_t last_index = history.entries().size() - 1;
  // The first triangle change of the last entry (a rewritten one) and its first appended.
  const std::size_t rewritten = last.first_triangle_change;
  const std::size_t appended = last.first_triangle_change + last.triangle_change_count -
                               (std::size_t{last.triangles_after} - last.triangles_before);
  const auto tc = [](const CheckpointLayout& l, std::size_t i) {
    return l.triangle_changes + i * kCheckpointTriangleChangeBytes;
  };
  const auto field_of = [](std::size_t entry, std::size_t offset, std::size_t n,
                           std::int64_t delta) {
    return [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
      const std::size_t at = entry_at(l, entry) + offset;
      put_le(b, at, n, get_le(b, at, n) + static_cast<std::uint64_t>(delta));
    };
  };
  const auto field = [=](std::size_t offset, std::size_t n, std::int64_t delta) {
    return field_of(last_index, offset, n, delta);
  };
  // The move (no topology) and the refined entry before it.
  const std::size_t move = last_index - 1;
  const std::size_t before_move = last_index - 2;
  return {
      {"version 1", [](Bytes& b, const CheckpointHeader&,
                       const CheckpointLayout&) { put_le(b, kHeaderVersion, 4, 1); }},
      {"mesh triangle index = vertex_count",
       [](Bytes& b, const CheckpointHeader& h, const CheckpointLayout& l) {
         put_le(b, l.triangles + 4, 4, h.vertex_count);
       }},
      {"a vertex count one less (the size no longer fits)",
       [](Bytes& b, const CheckpointHeader& h, const CheckpointLayout&) {
         put_le(b, kHeaderVertexCount, 4, h.vertex_count - 1);
       }},
      {"vertices_after beyond the capacity", field(kEntryVerticesAfter, 4, kSpare * 100)},
      {"vertices_before one more (count chain)", field(kEntryVerticesBefore, 4, 1)},
      {"triangles_before after triangles_after", field(kEntryTrianglesBefore, 4, 1'000'000)},
      {"triangles_after one less", field(kEntryTrianglesAfter, 4, -1)},
      {"first_triangle_change not contiguous", field(kEntryFirstTriangleChange, 8, 1)},
      {"triangle_change_count one less", field(kEntryTriangleChangeCount, 8, -1)},
      {"topology flag cleared", field(kEntryTopology, 1, -1)},
      {"topology fields in an entry without topology", field_of(move, kEntryVerticesBefore, 4, 5)},
      {"the undoable entries end at counts the mesh does not have",
       [=](Bytes& b, const CheckpointHeader& h, const CheckpointLayout& l) {
         field_of(before_move, kEntryVerticesAfter, 4, 1)(b, h, l);
         field_of(last_index, kEntryVerticesBefore, 4, 1)(b, h, l);
       }},
      {"rewritten triangle index = triangles_before",
       [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
         put_le(b, tc(l, rewritten), 4, last.triangles_before + 7);
       }},
      {"rewritten triangle's before index = vertices_before",
       [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
         put_le(b, tc(l, rewritten) + 4, 4, last.vertices_before);
       }},
      {"appended triangle out of order",
       [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
         put_le(b, tc(l, appended), 4, last.triangles_before + 1);
       }},
      {"appended triangle's after index = vertices_after",
       [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
         put_le(b, tc(l, appended) + 16 + 8, 4, last.vertices_after);
       }},
      {"vertex change index = its entry's vertices_after",
       [=](Bytes& b, const CheckpointHeader&, const CheckpointLayout& l) {
         put_le(b, l.changes + last.first_change * kCheckpointChangeBytes, 4, last.vertices_after);
       }},
  };
}

TEST(RefineCheckpoint, StructuralEditsWithTheRightCrcAreRefused) {
  auto live = refined_session(kSpare, kThreshold);
  const Bytes good = checkpoint_of(*live, 0);
  const CheckpointHeader h = header_of(good);
  const CheckpointLayout l = layout_of(h);
  ASSERT_EQ(l.crc + 4, good.size());
  auto target = std::make_unique<RefineStation>(3, kSpare, refine_config(kThreshold), false);
  auto untouched = std::make_unique<RefineStation>(3, kSpare, refine_config(kThreshold), false);
  Bytes resealed = good;
  reseal(resealed);
  ASSERT_EQ(resealed, good);
  ASSERT_TRUE(verify_bytes(good, *target).ok());
  for (const Edit& edit : structural_edits(live->session->history())) {
    Bytes bad = good;
    edit.apply(bad, h, l);
    reseal(bad);
    ASSERT_NE(bad, good) << edit.what;
    EXPECT_EQ(verify_bytes(bad, *target).code(), StatusCode::data_loss) << edit.what;
  }
  EXPECT_TRUE(same_session(*target, *untouched));
}

TEST(RefineCheckpoint, AnotherMeshCapacityIsRefused) {
  auto live = refined_session(kSpare, kThreshold);
  const Bytes bytes = checkpoint_of(*live, 0);
  auto other = std::make_unique<RefineStation>(3, kSpare + 1, refine_config(kThreshold), false);
  EXPECT_EQ(verify_bytes(bytes, *other).code(), StatusCode::data_loss);
}

// What no check of the file can see without replaying its history: a triangle of the
// mesh on a vertex that an undoable refined entry added although that entry did not
// write it. The file verifies and restores; the undo of that entry is refused and
// changes nothing (UndoHistory checks the triangles it leaves).
TEST(RefineCheckpoint, AMeshTriangleOnAVertexARefinedEntryAddedStopsItsUndo) {
  auto live = refined_session(kSpare, kThreshold);
  const session::UndoHistory& history = live->session->history();
  std::size_t k = history.undo_depth();
  while (k-- > 0 && !history.entries()[k].topology) {
  }
  ASSERT_LT(k, history.undo_depth());
  const std::uint32_t added = history.entries()[k].vertices_before;
  Bytes bytes = checkpoint_of(*live, 0);
  const CheckpointLayout l = layout_of(header_of(bytes));
  const session::UndoEntry& e = history.entries()[k];
  const auto rewritten_by_k = [&](std::size_t t) {
    for (std::size_t i = 0; i < e.triangle_change_count; ++i) {
      if (history.triangle_changes()[e.first_triangle_change + i].index == t) return true;
    }
    return false;
  };
  std::size_t t = 0;  // a triangle before it that entry k did not rewrite
  while (t < e.triangles_before && rewritten_by_k(t)) ++t;
  ASSERT_LT(t, e.triangles_before);
  put_le(bytes, l.triangles + t * kCheckpointTriangleBytes, 4, added);
  reseal(bytes);
  auto restored = std::make_unique<RefineStation>(3, kSpare, refine_config(kThreshold), false);
  ASSERT_TRUE(restore_bytes(bytes, *restored).ok());
  for (std::size_t undone = history.undo_depth() - 1; undone > k; --undone) {
    ASSERT_TRUE(restored->session->undo().ok());
  }
  const std::uint64_t before = restored->mesh().checksum();
  EXPECT_EQ(restored->session->undo().code(), StatusCode::out_of_range);
  EXPECT_EQ(restored->mesh().checksum(), before);
  EXPECT_EQ(restored->mesh().vertex_count(), history.entries()[k].vertices_after);
}

}  // namespace
}  // namespace twister::checkpoint
