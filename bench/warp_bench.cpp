// Vertex warps per second of the warp kernels against the paper-style baseline and a
// memory copy of the same bytes, all in one run (docs/performance.md, warp section).
//   Warp/<paper|scalar|simd>/<hands>/<vertices>  items_per_second = vertices warped
//   Copy/<vertices>                              the bytes a two-hand warp moves
//   Update/simd/2/<vertices>                     one live update: update() + apply()
// Every vertex lies in both hands' balls (the lens of two balls of radius 1 whose
// centres are 1 apart: no squash), so every row warps every vertex.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "twister/math/warp_plan.hpp"

namespace {

using twister::math::Frame;
using twister::math::KernelKind;
using twister::math::WarpMethod;
using twister::math::WarpPlan;

constexpr double kRadius = 1.0;

Frame turned(const Frame& f, glm::dvec3 axis, double angle, glm::dvec3 move) {
  const glm::dquat q = glm::angleAxis(angle, glm::normalize(axis));
  return Frame{f.origin + move, q * f.u, q * f.v, q * f.w};
}

struct Scene {
  std::vector<float> x, y, z, ox, oy, oz;
  std::vector<std::uint32_t> indices;
  std::vector<float> w1, w2;
  std::unique_ptr<WarpPlan> plan;
  std::array<Frame, 2> start, end, end_b;
};

std::unique_ptr<Scene> make_scene(std::size_t n, std::size_t hands) {
  auto s = std::make_unique<Scene>();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> ux(-0.5f, 0.5f), uyz(-0.87f, 0.87f);
  const glm::dvec3 o(-0.5, 0.0, 0.0), q(0.5, 0.0, 0.0);
  while (s->x.size() < n) {
    const glm::vec3 p(ux(rng), uyz(rng), uyz(rng));
    const glm::dvec3 pd(p);
    if (glm::length(pd - o) < 0.999 * kRadius && glm::length(pd - q) < 0.999 * kRadius) {
      s->x.push_back(p.x);
      s->y.push_back(p.y);
      s->z.push_back(p.z);
    }
  }
  s->ox = s->x;
  s->oy = s->y;
  s->oz = s->z;
  s->indices.resize(n);
  s->w1.resize(n);
  s->w2.resize(n);
  s->plan = std::make_unique<WarpPlan>(twister::math::WarpPlanStorage{s->indices, s->w1, s->w2});
  s->start = {twister::math::identity_frame(o), twister::math::identity_frame(q)};
  s->end = {turned(s->start[0], {0.2, 0.1, 1.0}, 1.3, {0.1, 0.6, 0.0}),
            turned(s->start[1], {0.1, 1.0, -0.3}, -1.1, {-0.1, 0.5, 0.2})};
  s->end_b = {turned(s->start[0], {0.2, 0.1, 1.0}, 1.35, {0.1, 0.62, 0.0}),
              turned(s->start[1], {0.1, 1.0, -0.3}, -1.05, {-0.1, 0.52, 0.2})};
  const twister::math::ConstVertexColumns rest(s->x, s->y, s->z);
  if (!s->plan->build(rest, std::span(s->start.data(), hands), kRadius, WarpMethod::twister).ok() ||
      !s->plan->update(std::span(s->end.data(), hands)).ok() || s->plan->indices().size() != n ||
      s->plan->influenced_count(hands - 1) != n) {
    std::fprintf(stderr, "warp_bench: scene set-up failed\n");
    std::abort();
  }
  return s;
}

Scene& scene(std::size_t n, std::size_t hands) {
  static std::map<std::pair<std::size_t, std::size_t>, std::unique_ptr<Scene>> cache;
  auto& s = cache[{n, hands}];
  if (!s) s = make_scene(n, hands);
  return *s;
}

// Largest distance between the float kernel's output and the double per-point warp,
// over a sample of the vertices, relative to the scene scale (1: the lens spans ~1.7).
double max_error(Scene& s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < s.x.size(); i += 61) {
    const glm::dvec3 exact = s.plan->warp_point(glm::dvec3(s.x[i], s.y[i], s.z[i]));
    worst = std::max(worst, glm::length(glm::dvec3(s.ox[i], s.oy[i], s.oz[i]) - exact));
  }
  return worst;
}

void warp_kernel(benchmark::State& state, KernelKind kind, std::size_t n, std::size_t hands) {
  Scene& s = scene(n, hands);
  s.plan->set_kernel(kind);
  const twister::math::ConstVertexColumns rest(s.x, s.y, s.z);
  const twister::math::VertexColumns out{s.ox, s.oy, s.oz};
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.plan->apply(rest, out));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["max_err"] = max_error(s);
}

// The paper's way: per vertex, the 4x4 matrix of S(t) = T(A + t d D) R(D, t a) T(-A)
// in double with std::sin/cos (inside glm::rotate), applied to the vertex.
void warp_paper(benchmark::State& state, std::size_t n, std::size_t hands) {
  Scene& s = scene(n, hands);
  const glm::dmat4 id(1.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec4 p(s.x[i], s.y[i], s.z[i], 1.0);
      glm::dvec4 moved = p;
      for (std::size_t h = 0; h < hands; ++h) {
        const twister::math::Screw& sc = s.plan->screw(h);
        const double t = h == 0 ? s.w1[i] : s.w2[i];
        const glm::dvec3 a = sc.axis_point();
        const glm::dmat4 m = glm::translate(id, a + t * sc.slide * sc.axis) *
                             glm::rotate(id, t * sc.angle, sc.axis) * glm::translate(id, -a);
        moved += m * p - p;
      }
      s.ox[i] = static_cast<float>(moved.x);
      s.oy[i] = static_cast<float>(moved.y);
      s.oz[i] = static_cast<float>(moved.z);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["max_err"] = max_error(s);
}

// A local memory limit: the same bytes as a two-hand warp (reads x, y, z, w1, w2;
// writes the three output columns), with no arithmetic beyond two adds that keep the
// weight columns from being optimised away.
__attribute__((noinline)) void stream_copy(const float* __restrict x, const float* __restrict y,
                                           const float* __restrict z, const float* __restrict w1,
                                           const float* __restrict w2, float* __restrict ox,
                                           float* __restrict oy, float* __restrict oz,
                                           std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    ox[i] = x[i];
    oy[i] = y[i];
    oz[i] = z[i] + (w1[i] + w2[i]);
  }
}

void copy_row(benchmark::State& state, std::size_t n) {
  Scene& s = scene(n, 2);
  for (auto _ : state) {
    stream_copy(s.x.data(), s.y.data(), s.z.data(), s.w1.data(), s.w2.data(), s.ox.data(),
                s.oy.data(), s.oz.data(), n);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

// One live update as the station does it per tracker record: new screws, warp.
void live_update(benchmark::State& state, std::size_t n) {
  Scene& s = scene(n, 2);
  s.plan->set_kernel(KernelKind::simd);
  const twister::math::ConstVertexColumns rest(s.x, s.y, s.z);
  const twister::math::VertexColumns out{s.ox, s.oy, s.oz};
  bool flip = false;
  for (auto _ : state) {
    flip = !flip;
    benchmark::DoNotOptimize(s.plan->update(flip ? s.end_b : s.end));
    benchmark::DoNotOptimize(s.plan->apply(rest, out));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("warp_bench: simd kernel dispatches to %s\n", twister::math::simd_kernel_isa());
  // Names built with snprintf: GCC 12 warns falsely (-Wrestrict) on string concatenation.
  char name[64];
  for (const std::size_t n : {30000u, 100000u, 1000000u}) {
    for (const std::size_t hands : {1u, 2u}) {
      std::snprintf(name, sizeof name, "Warp/paper/%zu/%zu", hands, n);
      benchmark::RegisterBenchmark(name, warp_paper, n, hands)->Unit(benchmark::kMillisecond);
      std::snprintf(name, sizeof name, "Warp/scalar/%zu/%zu", hands, n);
      benchmark::RegisterBenchmark(name, warp_kernel, KernelKind::scalar, n, hands)
          ->Unit(benchmark::kMillisecond);
      std::snprintf(name, sizeof name, "Warp/simd/%zu/%zu", hands, n);
      benchmark::RegisterBenchmark(name, warp_kernel, KernelKind::simd, n, hands)
          ->Unit(benchmark::kMillisecond);
    }
    std::snprintf(name, sizeof name, "Copy/%zu", n);
    benchmark::RegisterBenchmark(name, copy_row, n)->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("Update/simd/2/100000", live_update, std::size_t{100000})
      ->Unit(benchmark::kMicrosecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
