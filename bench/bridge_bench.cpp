// twister-bridge costs: link codec throughput for live-warp frames (encode,
// byte-wise decode) against a memcpy of the same bytes, and the offscreen frame
// time on Mesa llvmpipe of a live warp in the vertex shader vs the same mesh at
// rest (baseline: the warp's cost is the difference) and vs a CPU warp + upload.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "gl_context.hpp"
#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/screw.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace {

using namespace twister;

// Protocol 2: the stroke message once, then per update the compact hands message.
bridge::LiveMessages live_messages(std::uint8_t mask) {
  std::array<math::Frame, 2> start{};
  std::array<math::Frame, 2> end{};
  std::size_t k = 0;
  for (std::size_t h = 0; h < 2; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    start[k] = math::identity_frame({0.0, h == 0 ? -0.1 : 0.1, 0.0});
    end[k++] = math::frame_from_uv({0.0, h == 0 ? -0.15 : 0.15, -0.03}, {1.0, 0.0, 0.0},
                                   {0.0, 0.8253356149, 0.5646424734});
  }
  return bridge::make_live_messages(1, 1, math::WarpMethod::twister, 0.12, mask, start, end);
}

link::Hands live_message(std::uint8_t mask) { return live_messages(mask).hands; }

void BM_LiveFrameEncodeDecode(benchmark::State& state) {
  const auto m = live_message(static_cast<std::uint8_t>(state.range(0)));
  std::vector<std::byte> frame(link::kMaxFrameBytes);
  link::LinkDecoder decoder;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const auto n = link::encode_frame(m, frame);
    for (std::size_t i = 0; i < *n; ++i) benchmark::DoNotOptimize(decoder.process(frame[i]).ok());
    bytes += *n;
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.counters["frame_bytes"] =
      static_cast<double>(bytes) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_LiveFrameEncodeDecode)->Arg(1)->Arg(3);

void BM_LiveFrameMemcpyBaseline(benchmark::State& state) {
  std::vector<std::byte> a(640), b(640);
  for (auto _ : state) {
    std::memcpy(b.data(), a.data(), a.size());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 640);
}
BENCHMARK(BM_LiveFrameMemcpyBaseline);

struct GlFixture {
  std::unique_ptr<bridge::GlContext> context;
  bridge::MeshRenderer renderer;
  bridge::SceneReplica replica;
  bool ok = false;
};

GlFixture& gl() {
  static GlFixture f;
  static bool init = false;
  if (init) return f;
  init = true;
  ::unsetenv("DISPLAY");
  auto context = bridge::make_offscreen_context(800, 600);
  if (!context) return f;
  f.context = std::move(*context);
  if (!f.renderer.init(800, 600, true, {})) return f;
  static mesh::MeshWithStorage<110000, 220000> sphere;
  (void)meshio::make_sphere(sphere, 256, 400, 0.1F);  // ~102k vertices
  bridge::MeshData d;
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
  link::MeshEnd e;
  e = {1, *bridge::mesh_checksum(d)};
  (void)f.replica.apply(e);
  (void)f.replica.apply(live_messages(3).stroke);
  (void)f.replica.apply(live_messages(3).hands);
  f.renderer.set_mesh(f.replica.mesh(), false);
  f.renderer.set_weights(f.replica.live().weight1, f.replica.live().weight2);
  f.ok = f.replica.live().active;
  return f;
}

void BM_FrameRest(benchmark::State& state) {
  GlFixture& f = gl();
  if (!f.ok) {
    state.SkipWithError("no offscreen GL context");
    return;
  }
  f.renderer.set_mesh(f.replica.mesh(), true);
  f.renderer.set_live(nullptr);
  for (auto _ : state) f.renderer.draw();  // draw() ends with glFinish
  state.counters["vertices"] = static_cast<double>(f.replica.mesh().vertex_count());
}
BENCHMARK(BM_FrameRest)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_FrameLiveWarpInShader(benchmark::State& state) {
  GlFixture& f = gl();
  if (!f.ok) {
    state.SkipWithError("no offscreen GL context");
    return;
  }
  f.renderer.set_mesh(f.replica.mesh(), true);
  f.renderer.set_weights(f.replica.live().weight1, f.replica.live().weight2);
  for (auto _ : state) {
    f.renderer.set_live(&f.replica.live());
    f.renderer.draw();
  }
}
BENCHMARK(BM_FrameLiveWarpInShader)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_FrameCpuWarpAndUpload(benchmark::State& state) {
  GlFixture& f = gl();
  if (!f.ok) {
    state.SkipWithError("no offscreen GL context");
    return;
  }
  // As the bridge does for scodef: weights once per stroke, then per live frame the
  // CPU warp and an upload of the positions only.
  f.renderer.set_live(nullptr);
  f.renderer.set_mesh(f.replica.mesh(), true);
  f.renderer.set_weights(f.replica.live().weight1, f.replica.live().weight2);
  for (auto _ : state) {
    f.renderer.set_positions(f.replica.cpu_warp());
    f.renderer.draw();
  }
}
BENCHMARK(BM_FrameCpuWarpAndUpload)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
