// Cost of the sculpting session per tracker update and per committed stroke, against
// the bare warp it wraps, in one run (docs/performance.md, session section).
//   PlanUpdate/<n>     baseline: WarpPlan::update + apply (a live CPU warp of every
//                      influenced vertex)
//   SessionStep/<n>    SculptSession::set_hand + step while dragging (debounce,
//                      state machine, object-frame conversion, WarpPlan::update; no
//                      vertex is warped between commits since issue 24)
//   SessionStepLive/<n> the same plus live_positions(), as a consumer of the live
//                      positions at every record pays (update + apply: the station's
//                      step before issue 24)
//   SessionStroke/<n>  one whole stroke: grab (weights), one move, release (apply,
//                      undo record of every moved vertex, journal append + sync)
// The mesh is a UV sphere of radius 0.5 grabbed on its surface with radius 1, so
// every vertex is influenced (items_per_second counts vertices).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "counting_storage.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/session/sculpt_session.hpp"

namespace {

using namespace twister;

using bench::CountingStorage;

struct Rig {
  explicit Rig(std::size_t rings)
      : buffer(meshio::sphere_vertices(rings, 2 * rings),
               meshio::sphere_triangles(rings, 2 * rings)),
        writer(storage) {
    (void)meshio::make_sphere(buffer.mesh(), rings, 2 * rings, 0.5f);
    const std::size_t n = buffer.mesh().vertex_count();
    for (auto* v : {&lx, &ly, &lz, &w1, &w2}) v->resize(n);
    indices.resize(n);
    changes.resize(session::kDefaultUndoChanges);
    entries.resize(session::kDefaultUndoEntries);
    session::SculptSessionConfig config;
    for (auto& i : config.debounce.interval_us) i = 0;
    config.interaction.initial_radius_m = 1.0f;
    (void)writer.open();
    session = std::make_unique<session::SculptSession>(
        config, buffer.mesh(),
        session::SculptStorage{lx, ly, lz, math::WarpPlanStorage{indices, w1, w2}, changes,
                               entries},
        &writer);
  }
  math::Frame pose(double t) const {
    const double a = 0.3 * std::sin(t);
    return math::frame_from_uv({0.0, 0.0, 0.5 + 0.1 * std::sin(t)}, {std::cos(a), std::sin(a), 0.0},
                               {-std::sin(a), std::cos(a), 0.0});
  }
  void grab() {
    (void)session->set_hand(1, true, pose(0.0));
    (void)session->feed_button({3, true, now});
    (void)session->step(++now);
  }
  void release() {
    (void)session->feed_button({3, false, now});
    (void)session->step(++now);
  }

  meshio::MeshBuffer buffer;
  CountingStorage storage;
  journal::JournalWriter writer;
  std::vector<float> lx, ly, lz, w1, w2;
  std::vector<std::uint32_t> indices;
  std::vector<session::VertexChange> changes;
  std::vector<session::UndoEntry> entries;
  std::unique_ptr<session::SculptSession> session;
  ports::TimestampUs now = 0;
};

std::size_t rings_for(std::int64_t vertices) {
  return static_cast<std::size_t>(std::sqrt(static_cast<double>(vertices) / 2.0));
}

void PlanUpdate(benchmark::State& state) {
  Rig rig(rings_for(state.range(0)));
  rig.grab();
  const math::WarpPlan& plan = *rig.session->live().plan;
  // A private plan over the same rest columns, built like the session's.
  std::vector<std::uint32_t> idx(rig.indices.size());
  std::vector<float> a(idx.size()), b(idx.size()), ox(idx.size()), oy(idx.size()), oz(idx.size());
  math::WarpPlan bare(math::WarpPlanStorage{idx, a, b});
  const mesh::Mesh& m = rig.buffer.mesh();
  const math::ConstVertexColumns rest(m.x(), m.y(), m.z());
  const math::Frame start = plan.start_frame(0);
  (void)bare.build(rest, std::span(&start, 1), 1.0, math::WarpMethod::twister);
  double t = 0.0;
  for (auto _ : state) {
    const math::Frame end = rig.pose(t += 0.01);
    benchmark::DoNotOptimize(bare.update(std::span(&end, 1)));
    benchmark::DoNotOptimize(bare.apply(rest, math::VertexColumns{ox, oy, oz}));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(bare.indices().size()));
}

// One tracker record per iteration; with `ask_live` the live positions are asked
// for after every step as well (what the station did per record before issue 24).
void step_session(benchmark::State& state, bool ask_live) {
  Rig rig(rings_for(state.range(0)));
  rig.grab();
  double t = 0.0;
  for (auto _ : state) {
    (void)rig.session->set_hand(1, true, rig.pose(t += 0.01));
    benchmark::DoNotOptimize(rig.session->step(++rig.now));
    if (ask_live) benchmark::DoNotOptimize(rig.session->live_positions());
  }
  const auto influenced = static_cast<std::int64_t>(rig.session->live().plan->indices().size());
  if (!ask_live) state.counters["influenced"] = static_cast<double>(influenced);
  state.SetItemsProcessed(state.iterations() * influenced);
}

void SessionStep(benchmark::State& state) { step_session(state, false); }

void SessionStepLive(benchmark::State& state) { step_session(state, true); }

void SessionStroke(benchmark::State& state) {
  Rig rig(rings_for(state.range(0)));
  double t = 0.0;
  for (auto _ : state) {
    rig.grab();
    (void)rig.session->set_hand(1, true, rig.pose(t += 0.01));
    (void)rig.session->step(++rig.now);
    rig.release();
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(rig.buffer.mesh().vertex_count()));
}

BENCHMARK(PlanUpdate)->Arg(30'000)->Arg(100'000)->Unit(benchmark::kMicrosecond);
BENCHMARK(SessionStep)->Arg(30'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMicrosecond);
BENCHMARK(SessionStepLive)->Arg(30'000)->Arg(100'000)->Unit(benchmark::kMicrosecond);
BENCHMARK(SessionStroke)->Arg(30'000)->Arg(100'000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
