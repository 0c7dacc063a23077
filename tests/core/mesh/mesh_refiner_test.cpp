// MeshRefiner: the midpoint-error criterion met everywhere after refinement, a
// conforming manifold mesh after every split (also when a capacity stops it), the
// pre-existing triangles reported before they change, determinism, no allocation.
#include "twister/mesh/mesh_refiner.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "mesh_checks.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::mesh {
namespace {

using test_support::closed_manifold;
using test_support::edge_counts;
using test_support::edge_incidence;
using test_support::max_midpoint_error;

// A twist about z: the angle grows linearly with z (`turn` radians over `height`).
class Twist final : public PointWarp {
 public:
  Twist(double turn, double height) : rate_(turn / height) {}

 private:
  glm::dvec3 do_warp(glm::dvec3 p) const override {
    const double a = rate_ * p.z;
    return {std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
  }
  double rate_;
};

// Bends a plane: z += k x^2 (midpoint error of an edge = k dx^2 / 4).
class Bend final : public PointWarp {
 public:
  explicit Bend(double k) : k_(k) {}

 private:
  glm::dvec3 do_warp(glm::dvec3 p) const override { return {p.x, p.y, p.z + k_ * p.x * p.x}; }
  double k_;
};

class Identity final : public PointWarp {
  glm::dvec3 do_warp(glm::dvec3 p) const override { return p; }
};

constexpr std::size_t kMaxVertices = 40'000;
constexpr std::size_t kMaxTriangles = 2 * kMaxVertices;

MeshRefiner& refiner() {
  static auto* r = new MeshRefinerWithStorage<kMaxVertices, kMaxTriangles>();
  return *r;
}

std::unique_ptr<meshio::MeshBuffer> box(std::size_t n, std::size_t spare_vertices) {
  auto b = std::make_unique<meshio::MeshBuffer>(meshio::box_vertices(n) + spare_vertices,
                                                meshio::box_triangles(n) + 2 * spare_vertices);
  EXPECT_TRUE(meshio::make_box(b->mesh(), n, 0.5f).ok());
  return b;
}

const double kTurn170 = 170.0 * std::numbers::pi / 180.0;

TEST(MeshRefiner, TwistedBoxHasEveryEdgeWithinTheThreshold) {
  auto b = box(3, 20'000);
  Mesh& m = b->mesh();
  ASSERT_TRUE(closed_manifold(m));
  const Twist twist(kTurn170, 1.0);
  const double threshold = 0.002;
  EXPECT_GT(max_midpoint_error(m, twist), 0.1);
  const auto r = refiner().refine(m, twist, threshold);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->stop, RefineStop::done);
  EXPECT_EQ(r->blocked, 0u);
  EXPECT_EQ(m.vertex_count(), meshio::box_vertices(3) + r->edges_split);
  EXPECT_EQ(r->triangles_added, 2 * r->edges_split);  // closed: two triangles per split
  EXPECT_LE(max_midpoint_error(m, twist), threshold);
  EXPECT_TRUE(closed_manifold(m));
  for (std::uint32_t v = 26; v < m.vertex_count(); ++v) {
    const glm::dvec3 s = refiner().warped(v);
    EXPECT_EQ(s, twist.warp(glm::dvec3(m.position(v))));
  }
}

TEST(MeshRefiner, IdentityWarpSplitsNothing) {
  auto b = box(4, 100);
  const std::uint64_t before = b->mesh().checksum();
  const auto r = refiner().refine(b->mesh(), Identity{}, 1e-6);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->edges_split, 0u);
  EXPECT_EQ(b->mesh().checksum(), before);
}

TEST(MeshRefiner, AtVertexCapacityItStopsConforming) {
  auto b = box(3, 10);
  const auto r = refiner().refine(b->mesh(), Twist(kTurn170, 1.0), 0.001);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->stop, RefineStop::vertex_capacity);
  EXPECT_EQ(r->edges_split, 10u);
  EXPECT_TRUE(closed_manifold(b->mesh()));
}

TEST(MeshRefiner, AtTriangleCapacityItStopsConforming) {
  auto b = std::make_unique<meshio::MeshBuffer>(meshio::box_vertices(3) + 100,
                                                meshio::box_triangles(3) + 15);
  ASSERT_TRUE(meshio::make_box(b->mesh(), 3, 0.5f).ok());
  const auto r = refiner().refine(b->mesh(), Twist(kTurn170, 1.0), 0.001);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->stop, RefineStop::triangle_capacity);
  EXPECT_EQ(r->edges_split, 7u);  // 14 triangles; the 8th split needs two more than 1 left
  EXPECT_TRUE(closed_manifold(b->mesh()));
}

TEST(MeshRefiner, SameInputGivesTheSameBits) {
  auto a = box(3, 5'000);
  auto b = box(3, 5'000);
  const Twist twist(2.0, 1.0);
  ASSERT_TRUE(refiner().refine(a->mesh(), twist, 0.003).ok());
  ASSERT_TRUE(refiner().refine(b->mesh(), twist, 0.003).ok());
  EXPECT_EQ(a->mesh().checksum(), b->mesh().checksum());
}

// What undo needs: the reported triangles put back and the counts reset give the
// mesh before refinement, bit for bit.
class Recorder final : public RefineObserver {
 public:
  std::vector<std::pair<std::uint32_t, std::array<std::uint32_t, 3>>> changed;

 private:
  void do_triangle_changing(std::uint32_t t, const std::array<std::uint32_t, 3>& v) override {
    changed.emplace_back(t, v);
  }
};

TEST(MeshRefiner, ReportedTrianglesRestoreTheMeshBefore) {
  auto b = box(3, 2'000);
  Mesh& m = b->mesh();
  const std::uint64_t before = m.checksum();
  const std::size_t vertices = m.vertex_count(), triangles = m.triangle_count();
  Recorder rec;
  const auto r = refiner().refine(m, Twist(kTurn170, 1.0), 0.01, &rec);
  ASSERT_TRUE(r.ok());
  ASSERT_GT(r->edges_split, 0u);
  EXPECT_EQ(rec.changed.size(), r->triangles_changed);
  for (const auto& [t, v] : rec.changed) {
    EXPECT_LT(t, triangles);
    m.set_triangle(t, v);
  }
  ASSERT_TRUE(m.resize(vertices, triangles).ok());
  EXPECT_EQ(m.checksum(), before);
}

TEST(MeshRefiner, OpenGridStaysConformingInside) {
  constexpr std::size_t n = 5;
  meshio::MeshBuffer b(meshio::grid_vertices(n) + 5'000, meshio::grid_triangles(n) + 10'000);
  ASSERT_TRUE(meshio::make_grid(b.mesh(), n, 1.0f).ok());
  const Bend bend(0.5);
  const auto r = refiner().refine(b.mesh(), bend, 0.001);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->stop, RefineStop::done);
  EXPECT_LE(max_midpoint_error(b.mesh(), bend), 0.001);
  const auto incidence = edge_incidence(b.mesh());
  EXPECT_EQ(incidence.nonmanifold, 0u);
  EXPECT_EQ(incidence.same_direction, 0u);
  // An edge with one triangle lies on the square's border (a T-junction would not).
  for (const auto& [edge, count] : edge_counts(b.mesh())) {
    if (count != 1) continue;
    const glm::vec3 p = b.mesh().position(edge.first), q = b.mesh().position(edge.second);
    const bool border =
        (std::abs(p.x) == 1.0f && p.x == q.x) || (std::abs(p.y) == 1.0f && p.y == q.y);
    EXPECT_TRUE(border) << edge.first << "-" << edge.second;
  }
}

TEST(MeshRefiner, EdgeOfThreeTrianglesIsNeverSplit) {
  MeshWithStorage<64, 128> m;
  for (const glm::vec3 p : {glm::vec3(-1, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                            glm::vec3(0, -1, 0.5f), glm::vec3(0, -1, -0.5f)}) {
    (void)m.add_vertex(p);
  }
  (void)m.add_triangle(0, 1, 2);
  (void)m.add_triangle(1, 0, 3);
  (void)m.add_triangle(1, 0, 4);
  const auto r = refiner().refine(m, Bend(1.0), 0.01);
  ASSERT_TRUE(r.ok());
  EXPECT_GT(r->blocked, 0u);
  EXPECT_EQ(edge_counts(m).at({0, 1}), 3);
  EXPECT_EQ(edge_incidence(m).nonmanifold, 1u);
}

TEST(MeshRefiner, RefusesABadThresholdAndStorageTooSmall) {
  auto b = box(3, 0);
  EXPECT_EQ(refiner().refine(b->mesh(), Identity{}, 0.0).status().code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(refiner().refine(b->mesh(), Identity{}, std::nan("")).status().code(),
            StatusCode::invalid_argument);
  MeshRefinerWithStorage<8, 16> small;
  EXPECT_EQ(small.refine(b->mesh(), Identity{}, 0.1).status().code(),
            StatusCode::failed_precondition);
}

TEST(MeshRefiner, DoesNotAllocate) {
  auto b = box(3, 3'000);
  const Twist twist(kTurn170, 1.0);
  refiner().refine(b->mesh(), Identity{}, 1.0).status().ignore();  // first-call set-up
  EXPECT_NO_ALLOCATIONS({ refiner().refine(b->mesh(), twist, 0.002).status().ignore(); });
}

RC_GTEST_PROP(MeshRefinerProperty, ConformingAndWithinTheThresholdOrAtCapacity, ()) {
  const auto n = static_cast<std::size_t>(*rc::gen::inRange(2, 6));
  const auto spare = static_cast<std::size_t>(*rc::gen::inRange(0, 3000));
  const double turn = *rc::gen::inRange(-314, 315) / 100.0;
  const double threshold = *rc::gen::inRange(2, 50) / 1000.0;
  auto b = box(n, spare);
  const std::size_t vertices = b->mesh().vertex_count();
  const Twist twist(turn, 1.0);
  const auto r = refiner().refine(b->mesh(), twist, threshold);
  RC_ASSERT(r.ok());
  RC_ASSERT(closed_manifold(b->mesh()));
  RC_ASSERT(b->mesh().vertex_count() == vertices + r->edges_split);
  RC_ASSERT(r->triangles_added == 2 * r->edges_split);
  if (r->stop == RefineStop::done) RC_ASSERT(max_midpoint_error(b->mesh(), twist) <= threshold);
}

}  // namespace
}  // namespace twister::mesh
