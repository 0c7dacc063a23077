// Cost of adaptive refinement at commit (docs/performance.md, refinement section): the
// commit of one two-hand stroke on a 30k-vertex sphere, refined and not, in one run.
//   StrokeCommit/0          baseline: the release step that commits the stroke (warp of
//                           the influenced vertices into the mesh, undo entry, journal
//                           record), refinement off
//   StrokeCommit/<um>       the same commit with refinement on at a threshold of <um>
//                           micrometres: adjacency of the whole mesh, the midpoint error
//                           of every edge, the splits, the new vertices placed by the warp
//                           in double, their topology in the undo entry. At 500 um no
//                           edge needs a split (the cost of looking), at 200 um ~8k do.
//   StrokeCommit/<um>/<far>/<local>
//                           far = 1: the same sphere plus a 970k-vertex grid 10 m away
//                           (1M vertices, the stroke and what it influences unchanged);
//                           local = 1: refinement over the triangles the stroke's weights
//                           touch (refine_around, the default), 0: the whole mesh (before
//                           issue 24).
// Each iteration times the release step only; grab, motion and the undo that puts the
// mesh back for the next iteration run with the timer paused. Counters: vertices
// added per commit, influenced vertices.
// The stroke: a UV sphere of radius 0.5 m, one hand at each pole turning 90 degrees
// in opposite senses about the axis and pulling 5 cm outwards, radius 0.6 m.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "counting_storage.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/refiner_buffer.hpp"
#include "twister/session/sculpt_session.hpp"

namespace {

using namespace twister;

constexpr std::size_t kRings = 122;  // 2 * 122 segments: 29,770 vertices
constexpr std::size_t kSpare = 200'000;
constexpr std::size_t kFarGrid = 985;  // 970,225 vertices 10 m away: a 1M-vertex model

std::size_t far_vertices(bool far) { return far ? meshio::grid_vertices(kFarGrid) : 0; }
std::size_t far_triangles(bool far) { return far ? meshio::grid_triangles(kFarGrid) : 0; }

// The sphere, after the far grid when `far` (so the sphere's indices are large).
void make_model(mesh::Mesh& m, bool far) {
  if (!far) {
    (void)meshio::make_sphere(m, kRings, 2 * kRings, 0.5f);
    return;
  }
  (void)meshio::make_grid(m, kFarGrid, 2.0f);
  for (float& z : m.z()) z = 10.0f;
  meshio::MeshBuffer sphere(meshio::sphere_vertices(kRings, 2 * kRings),
                            meshio::sphere_triangles(kRings, 2 * kRings));
  (void)meshio::make_sphere(sphere.mesh(), kRings, 2 * kRings, 0.5f);
  const auto base = static_cast<std::uint32_t>(m.vertex_count());
  for (std::uint32_t v = 0; v < sphere.mesh().vertex_count(); ++v) {
    (void)m.add_vertex(sphere.mesh().position(v));
  }
  for (std::uint32_t t = 0; t < sphere.mesh().triangle_count(); ++t) {
    const auto tv = sphere.mesh().triangle(t);
    (void)m.add_triangle(base + tv[0], base + tv[1], base + tv[2]);
  }
}

using bench::CountingStorage;

struct Rig {
  Rig(double threshold_m, bool far, bool local)
      : buffer(meshio::sphere_vertices(kRings, 2 * kRings) + far_vertices(far) + kSpare,
               meshio::sphere_triangles(kRings, 2 * kRings) + far_triangles(far) + 2 * kSpare),
        refiner(buffer.mesh().vertex_capacity(), buffer.mesh().triangle_capacity()),
        writer(storage) {
    make_model(buffer.mesh(), far);
    const std::size_t n = buffer.mesh().vertex_capacity();
    for (auto* v : {&lx, &ly, &lz, &w1, &w2}) v->resize(n);
    indices.resize(n);
    changes.resize(session::kDefaultUndoChanges);
    entries.resize(session::kDefaultUndoEntries);
    triangles.resize(session::kDefaultUndoTriangleChanges);
    session::SculptSessionConfig config;
    for (auto& i : config.debounce.interval_us) i = 0;
    config.interaction.initial_radius_m = 0.6f;
    config.refine.enabled = threshold_m > 0.0;
    config.refine.threshold_m = threshold_m;
    config.refine.local = local;
    (void)writer.open();
    session = std::make_unique<session::SculptSession>(
        config, buffer.mesh(),
        session::SculptStorage{lx, ly, lz, math::WarpPlanStorage{indices, w1, w2}, changes, entries,
                               refiner.storage(), triangles},
        &writer);
  }
  // Hand h at its pole (z = +-0.5), turned by `turn` about z, pulled out by `pull`.
  static math::Frame pose(std::uint8_t h, double turn, double pull) {
    const double sense = h == 0 ? 1.0 : -1.0;
    const double a = sense * turn;
    return math::frame_from_uv({0.0, 0.0, sense * (0.5 + pull)}, {std::cos(a), std::sin(a), 0.0},
                               {-std::sin(a), std::cos(a), 0.0});
  }
  // Grab with both hands and twist (everything but the commit).
  void stroke() {
    for (std::uint8_t h = 0; h < 2; ++h) (void)session->set_hand(h, true, pose(h, 0.0, 0.0));
    (void)session->feed_button({0, true, now});
    (void)session->feed_button({3, true, now});
    (void)session->step(++now);
    for (int k = 1; k <= 4; ++k) {
      for (std::uint8_t h = 0; h < 2; ++h) {
        (void)session->set_hand(h, true, pose(h, k * std::numbers::pi / 8.0, k * 0.0125));
      }
      (void)session->step(++now);
    }
  }
  // Both hands let go: the commit.
  void release() {
    (void)session->feed_button({0, false, now});
    (void)session->feed_button({3, false, now});
    (void)session->step(++now);
  }

  meshio::MeshBuffer buffer;
  meshio::RefinerBuffer refiner;
  CountingStorage storage;
  journal::JournalWriter writer;
  std::vector<float> lx, ly, lz, w1, w2;
  std::vector<std::uint32_t> indices;
  std::vector<session::VertexChange> changes;
  std::vector<session::UndoEntry> entries;
  std::vector<session::TriangleChange> triangles;
  std::unique_ptr<session::SculptSession> session;
  ports::TimestampUs now = 0;
};

void StrokeCommit(benchmark::State& state) {
  Rig rig(static_cast<double>(state.range(0)) * 1e-6, state.range(1) != 0, state.range(2) != 0);
  const std::size_t vertices = rig.buffer.mesh().vertex_count();
  std::size_t added = 0;
  std::size_t influenced = 0;
  // One commit first: the refiner's adjacency is built once per topology (an undo of a
  // refined commit that split something costs one rebuild at the next commit).
  rig.stroke();
  rig.release();
  (void)rig.session->undo();
  for (auto _ : state) {
    state.PauseTiming();
    rig.stroke();
    influenced = rig.session->live().plan->indices().size();
    state.ResumeTiming();
    rig.release();
    state.PauseTiming();
    added = rig.buffer.mesh().vertex_count() - vertices;

    (void)rig.session->undo();  // the same mesh for the next commit
    state.ResumeTiming();
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["added"] = static_cast<double>(added);
  state.counters["influenced"] = static_cast<double>(influenced);
}

BENCHMARK(StrokeCommit)
    ->ArgNames({"um", "far", "local"})
    ->Args({0, 0, 1})
    ->Args({500, 0, 1})
    ->Args({200, 0, 1})
    ->Args({0, 1, 1})
    ->Args({500, 1, 1})
    ->Args({200, 1, 1})
    ->Args({500, 0, 0})
    ->Args({500, 1, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
