// What the sculptor's display costs per frame on Mesa llvmpipe (offscreen EGL,
// 800x600), at 30k and 100k vertices, in one run:
//   Plain/<n>        the baseline: the rest mesh alone (no weights, cues or HUD), as
//                    drawn: the closed sphere's back faces culled;
//   PlainNoCull/<n>  the same with both faces drawn (the frame before culling);
//   CuesHud/<n>      a two-hand stroke: warp in the shader with warped normals,
//                    weights, both hands' glyphs and spheres, the pink axes and
//                    yellow trajectories, the HUD (SceneView::draw, as twister-bridge);
//   CuesHudRefined/<n> the same stroke with the commit's refinement threshold
//                    (0.5 mm on the 0.2 m sphere): the live preview refined by the
//                    tessellation program every frame (issue 24);
//   CuesHudMoving/<n> before a grab with both hands moving every frame: the weight
//                    preview (a WarpPlan on the whole mesh) rebuilt per frame, plus
//                    cues and HUD.
//   Stage/<k>        (30k) the plain frame stage by stage, see BM_Stage.
// Counters vs and fs: vertex and fragment shader invocations of one frame.
// After the table: the ratio of each to Plain/<n> from this run, and of each stage
// to the whole two-sided frame (wall and CPU time; the fastest repetition of each).
#include <benchmark/benchmark.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <ctime>
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

constexpr int kWidth = 800;
constexpr int kHeight = 600;

// Seconds per frame of each row: wall clock, and the process's CPU time (with
// LP_NUM_THREADS=0 llvmpipe draws on the calling thread, so CPU time is the frame's
// work even on a machine shared with other jobs).
struct PerFrame {
  double wall = 0.0;
  double cpu = 0.0;
};
std::map<std::string, PerFrame>& seconds_per_frame() {
  static std::map<std::string, PerFrame> m;
  return m;
}

double cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Started before a row's loop; record() after it.
struct Timer {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpu_seconds();
};

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
  auto context = bridge::make_offscreen_context(kWidth, kHeight);
  if (!context) return nullptr;
  d->context = std::move(*context);
  if (!d->renderer.init(kWidth, kHeight, true, {})) return nullptr;
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

// With --benchmark_repetitions, the fastest repetition of each (the one the other
// jobs on the machine disturbed least).
void record(const benchmark::State& state, const std::string& name, const Timer& t0) {
  const auto n = static_cast<double>(state.iterations());
  const PerFrame now{
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0.wall).count() / n,
      (cpu_seconds() - t0.cpu) / n};
  const auto [it, added] =
      seconds_per_frame().try_emplace(name + "/" + std::to_string(state.range(0)), now);
  if (!added) it->second = {std::min(it->second.wall, now.wall), std::min(it->second.cpu, now.cpu)};
}

// Vertex shader and fragment shader invocations of one frame of `draw` (pipeline
// statistics; nothing where the driver cannot count them).
template <typename Draw>
void count_invocations(benchmark::State& state, Draw draw) {
  if (!epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) return;
  GLuint q[2] = {};
  glGenQueries(2, q);
  glBeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, q[0]);
  glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q[1]);
  draw();
  glEndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
  glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
  GLuint64 n[2] = {};
  glGetQueryObjectui64v(q[0], GL_QUERY_RESULT, &n[0]);
  glGetQueryObjectui64v(q[1], GL_QUERY_RESULT, &n[1]);
  glDeleteQueries(2, q);
  state.counters["vs"] = static_cast<double>(n[0]);
  state.counters["fs"] = static_cast<double>(n[1]);
}

void draw_plain(benchmark::State& state, const char* name, bool cull) {
  auto d = make_display(state.range(0));
  if (!d) return state.SkipWithError("no offscreen GL context");
  d->renderer.allow_face_culling(cull);
  if (d->renderer.culling_faces() != cull) return state.SkipWithError("culling is not as asked");
  count_invocations(state, [&] { d->renderer.draw(); });
  const Timer t0;
  for (auto _ : state) d->renderer.draw();  // draw() ends with glFinish
  record(state, name, t0);
  state.counters["vertices"] = static_cast<double>(d->renderer.vertex_count());
}

void BM_Plain(benchmark::State& state) { draw_plain(state, "Plain", true); }
void BM_PlainNoCull(benchmark::State& state) { draw_plain(state, "PlainNoCull", false); }

// Where llvmpipe spends the plain frame (both faces; each stage adds one step):
//   0 vertex shading only (GL_RASTERIZER_DISCARD: no primitive reaches the rasterizer);
//   1 + primitive assembly and clipping (the model moved out of the view: the clipper
//     rejects every triangle);
//   2 + triangle setup and binning (an 8x6 viewport: every triangle is set up,
//     next to no pixel is shaded);
//   3 + rasterization and fragment shading: the whole frame (PlainNoCull);
//   4 the whole frame culled (Plain).
void BM_Stage(benchmark::State& state) {
  auto d = make_display(30000);
  if (!d) return state.SkipWithError("no offscreen GL context");
  const long stage = state.range(0);
  d->renderer.allow_face_culling(stage == 4);
  if (stage == 1) d->renderer.set_object_pose(math::identity_frame({0.0, 0.0, 5.0}));
  const auto frame = [&] {
    d->renderer.begin_frame();
    if (stage == 0) glEnable(GL_RASTERIZER_DISCARD);
    if (stage == 2) glViewport(0, 0, 8, 6);
    d->renderer.draw_mesh();
    glDisable(GL_RASTERIZER_DISCARD);
    d->renderer.end_frame();
  };
  count_invocations(state, frame);
  const Timer t0;
  for (auto _ : state) frame();
  record(state, "Stage", t0);
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
  count_invocations(state, [&] { d->app->draw(); });
  const Timer t0;
  for (auto _ : state) d->app->draw();
  record(state, name, t0);
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
  const Timer t0;
  for (auto _ : state) {
    phase += 0.01;  // 1 mm per frame: every frame rebuilds the preview
    m.hands[0] = link::to_compact(math::identity_frame({0.0, -0.1 - 0.01 * std::sin(phase), 0.0}));
    m.hands[1] = link::to_compact(math::identity_frame({0.0, 0.1, 0.01 * std::sin(phase)}));
    ++m.sequence;
    (void)d->app->replica().apply(m);
    d->app->step();
    d->app->draw();
  }
  record(state, "CuesHudMoving", t0);
  count_invocations(state, [&] { d->app->draw(); });
}

BENCHMARK(BM_Plain)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_PlainNoCull)
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

BENCHMARK(BM_Stage)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  const auto ratio = [](const std::string& row, const std::string& base, const char* what) {
    const auto& m = seconds_per_frame();
    if (m.count(row) == 0 || m.count(base) == 0) return;
    const PerFrame r = m.at(row);
    const PerFrame b = m.at(base);
    std::printf("ratio %s vs %s%s: %.2f wall (%.2f ms vs %.2f ms), %.2f cpu (%.2f ms vs %.2f ms)\n",
                row.c_str(), base.c_str(), what, r.wall / b.wall, 1e3 * r.wall, 1e3 * b.wall,
                r.cpu / b.cpu, 1e3 * r.cpu, 1e3 * b.cpu);
  };
  for (const std::string n : {"30000", "100000"}) {
    ratio("Plain/" + n, "PlainNoCull/" + n, "");
    for (const char* row : {"CuesHud", "CuesHudRefined", "CuesHudMoving"}) {
      ratio(row + ("/" + n), "Plain/" + n, "");
    }
  }
  for (int k = 0; k <= 4; ++k) {
    ratio("Stage/" + std::to_string(k), "Stage/3", " (the whole two-sided frame)");
  }
  return 0;
}
