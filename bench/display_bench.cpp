// What the sculptor's display costs per frame on Mesa llvmpipe (offscreen EGL,
// 800x600), at 30k and 100k vertices, in one run:
//   Plain/<n>        the baseline: the rest mesh alone (no weights, cues or HUD);
//   CuesHud/<n>      a two-hand stroke: warp in the shader with warped normals,
//                    weights, both hands' glyphs and spheres, the pink axes and
//                    yellow trajectories, the HUD (SceneView::draw, as twister-bridge);
//   CuesHudRefined/<n> the same stroke with the commit's refinement threshold
//                    (0.5 mm on the 0.2 m sphere): the live preview refined by the
//                    tessellation program every frame (issue 24);
//   CuesHudMoving/<n> before a grab with both hands moving every frame: the weight
//                    preview (a WarpPlan on the whole mesh) rebuilt per frame, plus
//                    cues and HUD.
// After the table: the ratio of each to Plain/<n> from this run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "bridge_app.hpp"
#include "gl_context.hpp"
#include "scene_view.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace {

using namespace twister;

std::map<std::string, double>& seconds_per_frame() {
  static std::map<std::string, double> m;
  return m;
}

class QuietLink final : public ports::LinkPort {
  Result<std::size_t> do_send(std::span<const std::byte> src) override { return src.size(); }
  Result<std::size_t> do_receive(std::span<std::byte>) override { return std::size_t{0}; }
};

struct Display {
  std::unique_ptr<bridge::GlContext> context;
  bridge::MeshRenderer renderer;
  hal::MonotonicClock clock;
  std::unique_ptr<bridge::SceneView> view;
  QuietLink link;
  ports::NullLogSink log;
  std::unique_ptr<bridge::BridgeApp> app;
};

// The sphere of about `n` vertices (0.1 m) in a fresh display.
std::unique_ptr<Display> make_display(long n) {
  ::unsetenv("DISPLAY");
  auto d = std::make_unique<Display>();
  auto context = bridge::make_offscreen_context(800, 600);
  if (!context) return nullptr;
  d->context = std::move(*context);
  if (!d->renderer.init(800, 600, true, {})) return nullptr;
  d->view = std::make_unique<bridge::SceneView>(d->renderer, d->clock);
  if (!d->view->init()) return nullptr;
  d->app = std::make_unique<bridge::BridgeApp>(d->link, d->clock, &d->renderer,
                                               bridge::BridgeOptions{}, d->log);
  d->app->set_view(d->view.get());
  static mesh::MeshWithStorage<110000, 220000> sphere;
  sphere.clear();
  const std::size_t rings = n > 50000 ? 256 : 150;
  (void)meshio::make_sphere(sphere, rings, n > 50000 ? 400 : 200, 0.1F);
  const auto nv = static_cast<std::uint32_t>(sphere.vertex_count());
  const auto nt = static_cast<std::uint32_t>(sphere.triangle_count());
  (void)d->app->replica().apply(link::MeshBegin{true, 0, 1, nv, nt});
  static link::Vertices v;
  v.count = 0;
  for (std::uint32_t i = 0; i < nv; ++i) {
    v.items[v.count++] = {i, sphere.x()[i], sphere.y()[i], sphere.z()[i]};
    if (v.count == link::kMaxVerticesPerChunk || i + 1 == nv) {
      (void)d->app->replica().apply(v);
      v.count = 0;
    }
  }
  static link::Triangles t;
  const auto idx = sphere.triangle_indices();
  for (std::uint32_t k = 0; k < nt; k += link::kMaxTrianglesPerChunk) {
    t.first = k;
    t.count =
        static_cast<std::uint16_t>(std::min<std::size_t>(link::kMaxTrianglesPerChunk, nt - k));
    std::copy_n(idx.begin() + 3 * static_cast<std::ptrdiff_t>(k), 3 * t.count, t.indices.begin());
    (void)d->app->replica().apply(t);
  }
  (void)d->app->replica().apply(link::MeshEnd{1, sphere.checksum()});
  link::StatusReport status;
  status.tracker_state = 1;
  status.tracker_rate_hz = 120.0F;
  (void)d->app->replica().apply(status);
  d->app->step();
  return d;
}

void record(const benchmark::State& state, const std::string& name, double seconds) {
  seconds_per_frame()[name + "/" + std::to_string(state.range(0))] =
      seconds / static_cast<double>(state.iterations());
}

void BM_Plain(benchmark::State& state) {
  auto d = make_display(state.range(0));
  if (!d) return state.SkipWithError("no offscreen GL context");
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) d->renderer.draw();  // draw() ends with glFinish
  record(state, "Plain",
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  state.counters["vertices"] = static_cast<double>(d->renderer.vertex_count());
}

// A two-hand stroke on the sphere, refined live to `threshold_m` (0: not refined).
void draw_stroke(benchmark::State& state, const char* name, float threshold_m) {
  auto d = make_display(state.range(0));
  if (!d) return state.SkipWithError("no offscreen GL context");
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}),
                                         math::identity_frame({0.0, 0.1, 0.0})};
  const auto turned = [](glm::dvec3 o, double a) {
    return math::frame_from_uv(o, {1.0, 0.0, 0.0}, {0.0, std::cos(a), std::sin(a)});
  };
  const std::array<math::Frame, 2> end{turned({0.02, -0.14, -0.03}, 0.7),
                                       turned({0.02, 0.14, -0.03}, -0.7)};
  auto live = bridge::make_live_messages(1, 1, math::WarpMethod::twister, 0.08, 3, start, end);
  live.stroke.refine_threshold_m = threshold_m;
  (void)d->app->replica().apply(live.stroke);
  (void)d->app->replica().apply(live.hands);
  d->app->step();
  if ((threshold_m > 0.0F) != d->renderer.refining_live()) {
    return state.SkipWithError("the refined program is not what draws");
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) d->app->draw();
  record(state, name,
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  if (threshold_m > 0.0F) {
    state.counters["preview_triangles"] =
        static_cast<double>(d->renderer.capture_live_surface().rest.size() / 3);
  }
}

void BM_CuesHud(benchmark::State& state) { draw_stroke(state, "CuesHud", 0.0F); }

void BM_CuesHudRefined(benchmark::State& state) {
  draw_stroke(state, "CuesHudRefined", 0.0005F);
}

void BM_CuesHudMoving(benchmark::State& state) {
  auto d = make_display(state.range(0));
  if (!d) return state.SkipWithError("no offscreen GL context");
  link::Hands m;
  m.radius_m = 0.08F;
  m.flags = link::kHandSample0 | link::kHandSample1 | link::kHandTracked0 | link::kHandTracked1;
  double phase = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    phase += 0.01;  // 1 mm per frame: every frame rebuilds the preview
    m.hands[0] = link::to_compact(math::identity_frame({0.0, -0.1 - 0.01 * std::sin(phase), 0.0}));
    m.hands[1] = link::to_compact(math::identity_frame({0.0, 0.1, 0.01 * std::sin(phase)}));
    ++m.sequence;
    (void)d->app->replica().apply(m);
    d->app->step();
    d->app->draw();
  }
  record(state, "CuesHudMoving",
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

BENCHMARK(BM_Plain)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CuesHud)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CuesHudRefined)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CuesHudMoving)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  for (const char* n : {"30000", "100000"}) {
    const double plain = seconds_per_frame()[std::string("Plain/") + n];
    if (plain <= 0.0) continue;
    for (const char* row : {"CuesHud", "CuesHudRefined", "CuesHudMoving"}) {
      const double t = seconds_per_frame()[std::string(row) + "/" + n];
      std::printf("ratio %s/%s vs Plain/%s: %.2f (%.2f ms vs %.2f ms per frame)\n", row, n, n,
                  t / plain, 1e3 * t, 1e3 * plain);
    }
  }
  return 0;
}
