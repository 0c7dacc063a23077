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

using bench::CountingStorage;

struct Rig {
  explicit Rig(double threshold_m)
      : buffer(meshio::sphere_vertices(kRings, 2 * kRings) + kSpare,
               meshio::sphere_triangles(kRings, 2 * kRings) + 2 * kSpare),
        refiner(buffer.mesh().vertex_capacity(), buffer.mesh().triangle_capacity()),
        writer(storage) {
    (void)meshio::make_sphere(buffer.mesh(), kRings, 2 * kRings, 0.5f);
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
  Rig rig(static_cast<double>(state.range(0)) * 1e-6);
  const std::size_t vertices = rig.buffer.mesh().vertex_count();
  std::size_t added = 0;
  std::size_t influenced = 0;
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

BENCHMARK(StrokeCommit)->Arg(0)->Arg(500)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
