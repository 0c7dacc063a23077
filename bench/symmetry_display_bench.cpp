// The display's per-frame cost of a symmetric live stroke (issue 26), offscreen on Mesa
// llvmpipe (EGL surfaceless + FBO, 800x600, each frame ending with glFinish), on the
// spork's starting mesh (a sphere of 0.30 m, ~10k vertices, radius 0.45 m: every ball
// reaches most of the sphere), two hands, rows in one run:
//   Plain           baseline: the same two-hand stroke without symmetry, warped in the
//                   plain vertex shader (hands update + set_live + draw)
//   Cpu/<group>     the CPU path twister-bridge took for every symmetric stroke before:
//                   hands update, SceneReplica::cpu_warp (the plan's float path),
//                   MeshRenderer::set_positions (positions and normals uploaded), draw
//   Shader/<group>  the symmetric program: hands update (the images' screws), set_live
//                   (the images' uniform block), draw
//   Grab/<group>    once per grab: the plan and the shader's entries (weights of every
//                   image with their gradients) built by the replica, and their upload
// group 0: rot6 about z, 1: rot12 + mirror about z. After the table each row's time over
// Plain's of the same run (CPU time and wall time; medians with repetitions: run with
// LP_NUM_THREADS=0, docs/performance.md).
#include <benchmark/benchmark.h>
#include <epoxy/gl.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <string>

#include "gl_context.hpp"
#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace {

using namespace twister;

constexpr std::array<math::SymmetrySpec, 2> kGroups{
    {{math::SymmetryKind::rotation, 0, 2, 6}, {math::SymmetryKind::rotation_mirror, 0, 2, 12}}};
constexpr const char* kGroupNames[] = {"rot6", "rot12m"};

struct Fixture {
  std::unique_ptr<bridge::GlContext> context;
  bridge::MeshRenderer renderer;
  bridge::SceneReplica replica;
  bridge::MeshData mesh;
  std::uint32_t stroke = 0;
  bool ok = false;
};

Fixture& fixture() {
  static Fixture f;
  static bool init = false;
  if (init) return f;
  init = true;
  ::unsetenv("DISPLAY");
  auto context = bridge::make_offscreen_context(800, 600);
  if (!context) return f;
  f.context = std::move(*context);
  if (!f.renderer.init(800, 600, true, {})) return f;
  static mesh::MeshWithStorage<12000, 24000> sphere;
  (void)meshio::make_sphere(sphere, 72, 140, 0.3F);  // 9,942 vertices
  bridge::MeshData& d = f.mesh;
  d.x.assign(sphere.x().begin(), sphere.x().end());
  d.y.assign(sphere.y().begin(), sphere.y().end());
  d.z.assign(sphere.z().begin(), sphere.z().end());
  d.indices.assign(sphere.triangle_indices().begin(), sphere.triangle_indices().end());
  link::MeshBegin b;
  b = {true, 0, 1, static_cast<std::uint32_t>(d.vertex_count()),
       static_cast<std::uint32_t>(d.triangle_count())};
  (void)f.replica.apply(b);
  link::Vertices v;
  for (std::uint32_t i = 0; i < d.vertex_count(); ++i) {
    v.items[v.count++] = {i, d.x[i], d.y[i], d.z[i]};
    if (v.count == link::kMaxVerticesPerChunk || i + 1 == d.vertex_count()) {
      (void)f.replica.apply(v);
      v.count = 0;
    }
  }
  link::Triangles t;
  for (std::uint32_t k = 0; k < d.triangle_count(); k += link::kMaxTrianglesPerChunk) {
    const auto n = std::min<std::size_t>(link::kMaxTrianglesPerChunk, d.triangle_count() - k);
    t.first = k;
    t.count = static_cast<std::uint16_t>(n);
    std::copy_n(d.indices.begin() + 3 * static_cast<std::ptrdiff_t>(k), 3 * n, t.indices.begin());
    (void)f.replica.apply(t);
  }
  (void)f.replica.apply(link::MeshEnd{1, *bridge::mesh_checksum(d)});
  f.renderer.set_mesh(f.replica.mesh(), false);
  f.renderer.allow_face_culling(false);
  f.ok = true;
  return f;
}

// A new two-hand stroke (the spork's second stroke's scale: grab points on the sphere,
// pulled out 6 cm and turned 0.6 rad) under `group` (kind none: plain).
bridge::LiveMessages stroke(Fixture& f, const math::SymmetrySpec& group) {
  const glm::dvec3 g0 = 0.3 * glm::normalize(glm::dvec3{0.8, 0.3, 0.5});
  const glm::dvec3 g1 = 0.3 * glm::normalize(glm::dvec3{-0.4, 0.7, -0.6});
  const std::array<math::Frame, 2> start{math::identity_frame(g0), math::identity_frame(g1)};
  const std::array<math::Frame, 2> end{
      math::frame_from_uv(g0 + 0.06 * glm::normalize(g0), {1.0, 0.0, 0.0},
                          {0.0, std::cos(0.6), std::sin(0.6)}),
      math::frame_from_uv(g1 + 0.06 * glm::normalize(g1), {std::cos(0.6), std::sin(0.6), 0.0},
                          {-std::sin(0.6), std::cos(0.6), 0.0})};
  bridge::LiveMessages m =
      bridge::make_live_messages(1, ++f.stroke, math::WarpMethod::twister, 0.45, 3, start, end);
  m.stroke.symmetry = {static_cast<std::uint8_t>(group.kind), group.mirrors, group.axis,
                       group.order};
  return m;
}

struct PerFrame {
  double wall = 0.0;
  double cpu = 0.0;
};
std::map<std::string, PerFrame>& per_frame() {
  static std::map<std::string, PerFrame> m;
  return m;
}
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
struct Timer {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpu_seconds();
};
// With repetitions, the fastest (the least disturbed by the machine's other jobs).
void record(const benchmark::State& state, const std::string& name, const Timer& t0) {
  const auto n = static_cast<double>(state.iterations());
  const PerFrame now{
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0.wall).count() / n,
      (cpu_seconds() - t0.cpu) / n};
  const auto [it, added] = per_frame().try_emplace(name, now);
  if (!added) it->second = {std::min(it->second.wall, now.wall), std::min(it->second.cpu, now.cpu)};
}

// Starts `m`'s stroke on the replica and shows its weights, as twister-bridge does.
bool begin(Fixture& f, const bridge::LiveMessages& m) {
  (void)f.replica.apply(m.stroke);
  (void)f.replica.apply(m.hands);
  f.renderer.set_mesh(f.replica.mesh(), true);
  f.renderer.set_weights(f.replica.live().weight1, f.replica.live().weight2);
  f.renderer.set_gradients(f.replica.live().gradient1, f.replica.live().gradient2);
  return f.replica.live().active;
}

void BM_Plain(benchmark::State& state) {
  Fixture& f = fixture();
  bridge::LiveMessages m = stroke(f, {});
  if (!f.ok || !begin(f, m)) {
    state.SkipWithError("no offscreen GL context or no stroke");
    return;
  }
  const Timer t0;
  for (auto _ : state) {
    ++m.hands.sequence;
    (void)f.replica.apply(m.hands);
    f.renderer.set_live(&f.replica.live());
    f.renderer.draw();
  }
  record(state, "Plain", t0);
}
BENCHMARK(BM_Plain)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

void BM_Cpu(benchmark::State& state) {
  Fixture& f = fixture();
  bridge::LiveMessages m = stroke(f, kGroups[static_cast<std::size_t>(state.range(0))]);
  if (!f.ok || !begin(f, m)) {
    state.SkipWithError("no offscreen GL context or no stroke");
    return;
  }
  f.renderer.allow_symmetric_shader(false);
  const Timer t0;
  for (auto _ : state) {
    ++m.hands.sequence;
    (void)f.replica.apply(m.hands);
    f.renderer.set_positions(f.replica.cpu_warp());
    f.renderer.set_live(&f.replica.live());
    f.renderer.draw();
  }
  record(state, std::string("Cpu/") + kGroupNames[state.range(0)], t0);
  f.renderer.allow_symmetric_shader(true);
}
BENCHMARK(BM_Cpu)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

void BM_Shader(benchmark::State& state) {
  Fixture& f = fixture();
  bridge::LiveMessages m = stroke(f, kGroups[static_cast<std::size_t>(state.range(0))]);
  if (!f.ok || !begin(f, m) || !f.renderer.warps_on_gpu(f.replica.live())) {
    state.SkipWithError("no offscreen GL context, no stroke or no symmetric program");
    return;
  }
  const Timer t0;
  for (auto _ : state) {
    ++m.hands.sequence;
    (void)f.replica.apply(m.hands);
    f.renderer.set_live(&f.replica.live());
    f.renderer.draw();
  }
  record(state, std::string("Shader/") + kGroupNames[state.range(0)], t0);
  state.counters["entries"] = static_cast<double>(f.replica.live().symmetric_gpu.entry_count());
}
BENCHMARK(BM_Shader)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

void BM_Grab(benchmark::State& state) {
  Fixture& f = fixture();
  if (!f.ok) {
    state.SkipWithError("no offscreen GL context");
    return;
  }
  const math::SymmetrySpec group = kGroups[static_cast<std::size_t>(state.range(0))];
  const Timer t0;
  for (auto _ : state) {
    const bridge::LiveMessages m = stroke(f, group);
    (void)f.replica.apply(m.stroke);
    (void)f.replica.apply(m.hands);  // builds the plan and the entries
    f.renderer.set_live(&f.replica.live());
    glFinish();
  }
  record(state, std::string("Grab/") + kGroupNames[state.range(0)], t0);
}
BENCHMARK(BM_Grab)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  const auto& m = per_frame();
  if (m.count("Plain") == 0) return 0;
  const PerFrame b = m.at("Plain");
  for (const auto& [name, r] : m) {
    std::printf(
        "ratio %s vs Plain: %.2f cpu (%.2f ms vs %.2f ms), %.2f wall (%.2f ms vs %.2f ms)\n",
        name.c_str(), r.cpu / b.cpu, 1e3 * r.cpu, 1e3 * b.cpu, r.wall / b.wall, 1e3 * r.wall,
        1e3 * b.wall);
  }
  return 0;
}
