// UndoHistory with topology (issue 13): a refined commit undone and redone gives the
// mesh before and after it bit for bit (positions, counts, triangles), in order with
// plain position entries; a refinement larger than the triangle pool is not kept;
// dropping old entries keeps both pools consistent.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "twister/mesh/mesh_refiner.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/session/undo_history.hpp"

namespace twister::session {
namespace {

class Twist final : public mesh::PointWarp {
  glm::dvec3 do_warp(glm::dvec3 p) const override {
    const double a = 2.5 * p.z;
    return {std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
  }
};

class ToHistory final : public mesh::RefineObserver {
 public:
  explicit ToHistory(UndoHistory& h) : h_(h) {}
  Status status;

 private:
  void do_triangle_changing(std::uint32_t t, const std::array<std::uint32_t, 3>& v) override {
    if (const Status s = h_.record_triangle(t, v); !s.ok()) status = s;
  }
  UndoHistory& h_;
};

mesh::MeshRefiner& refiner() {
  static auto* r = new mesh::MeshRefinerWithStorage<4000, 8000>();
  return *r;
}

// One commit the way SessionHistory makes it: refine at rest, then every vertex
// to its warped position (old ones recorded before -> after, new ones appended).
Status refined_commit(UndoHistory& h, mesh::Mesh& m, double threshold) {
  const Twist twist;
  const auto vertices = static_cast<std::uint32_t>(m.vertex_count());
  const auto triangles = static_cast<std::uint32_t>(m.triangle_count());
  h.begin_entry();
  ToHistory observer(h);
  const auto refined = refiner().refine(m, twist, threshold, &observer);
  EXPECT_TRUE(refined.ok());
  Status s = observer.status;
  for (std::uint32_t v = 0; v < m.vertex_count(); ++v) {
    const glm::vec3 after(v < vertices ? twist.warp(glm::dvec3(m.position(v)))
                                       : refiner().warped(v));
    if (const Status r = h.record(v, m.position(v), after); !r.ok()) s = r;
    m.set_position(v, after);
  }
  if (const Status r = h.record_topology(m, vertices, triangles); !r.ok()) s = r;
  const Status closed = h.end_entry();
  return s.ok() ? closed : s;
}

std::unique_ptr<meshio::MeshBuffer> box() {
  auto b = std::make_unique<meshio::MeshBuffer>(4000, 8000);
  EXPECT_TRUE(meshio::make_box(b->mesh(), 3, 0.5f).ok());
  return b;
}

TEST(UndoTopology, RefinedCommitsUndoAndRedoBitIdentically) {
  auto b = box();
  mesh::Mesh& m = b->mesh();
  UndoHistoryWithStorage<1 << 14, 8> h;
  const std::uint64_t c0 = m.checksum();
  ASSERT_TRUE(refined_commit(h, m, 0.01).ok());
  const std::uint64_t c1 = m.checksum();
  const std::size_t v1 = m.vertex_count();
  ASSERT_GT(v1, 26u);
  m.set_position(3, {0.25f, 0.5f, 0.75f});  // a plain position entry in between
  ASSERT_TRUE(refined_commit(h, m, 0.004).ok());
  const std::uint64_t c2 = m.checksum();
  ASSERT_GT(m.vertex_count(), v1);
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_EQ(m.vertex_count(), v1);
  EXPECT_EQ(m.position(3), glm::vec3(0.25f, 0.5f, 0.75f));
  ASSERT_TRUE(h.undo(m).ok());
  EXPECT_EQ(m.checksum(), c0);
  ASSERT_TRUE(h.redo(m).ok());
  m.set_position(3, {0.25f, 0.5f, 0.75f});
  ASSERT_TRUE(h.redo(m).ok());
  EXPECT_EQ(m.checksum(), c2);
  ASSERT_TRUE(h.undo(m).ok());
  ASSERT_TRUE(h.undo(m).ok());
  ASSERT_TRUE(h.redo(m).ok());
  EXPECT_EQ(m.checksum(), c1);
}

TEST(UndoTopology, AMeshOfOtherCountsIsRefused) {
  auto b = box();
  UndoHistoryWithStorage<1 << 14, 8> h;
  ASSERT_TRUE(refined_commit(h, b->mesh(), 0.01).ok());
  auto other = box();
  EXPECT_EQ(h.undo(other->mesh()).status().code(), StatusCode::out_of_range);
  EXPECT_EQ(other->mesh().vertex_count(), 26u);
  ASSERT_TRUE(h.undo(b->mesh()).ok());
  EXPECT_EQ(h.redo(other->mesh()).status().code(), StatusCode::ok);  // same counts: fits
}

TEST(UndoTopology, RefinementLargerThanTheTrianglePoolIsNotUndoable) {
  auto b = box();
  std::array<VertexChange, 4096> changes{};
  std::array<UndoEntry, 4> entries{};
  std::array<TriangleChange, 40> triangles{};
  UndoHistory h(changes, entries, triangles);
  b->mesh().set_position(0, b->mesh().position(0));
  EXPECT_EQ(refined_commit(h, b->mesh(), 0.004).code(), StatusCode::resource_exhausted);
  EXPECT_FALSE(h.can_undo());
  UndoHistory none(changes, entries);  // no triangle pool at all
  EXPECT_EQ(refined_commit(none, b->mesh(), 0.002).code(), StatusCode::resource_exhausted);
}

TEST(UndoTopology, OldEntriesMakeRoomInBothPools) {
  auto b = box();
  mesh::Mesh& m = b->mesh();
  std::array<VertexChange, 4096> changes{};
  std::array<UndoEntry, 8> entries{};
  std::array<TriangleChange, 4000> triangles{};  // the third alone needs ~3100
  UndoHistory h(changes, entries, triangles);
  for (const double threshold : {0.02, 0.01, 0.006}) {
    ASSERT_TRUE(refined_commit(h, m, threshold).ok()) << threshold;
  }
  EXPECT_GE(h.dropped_entries(), 1u);
  EXPECT_EQ(h.undo_depth(), 3u - h.dropped_entries());
  const std::uint64_t last = m.checksum();
  ASSERT_TRUE(h.undo(m).ok());
  ASSERT_TRUE(h.redo(m).ok());
  EXPECT_EQ(m.checksum(), last);
}

}  // namespace
}  // namespace twister::session
