// The cost of a symmetric stroke's update (issue 26, docs/math.md §11) against the
// two-hand update without symmetry on the same mesh, in the same run
// (docs/performance.md, symmetry section), two rows per group:
//   Commit/<group>/<k>   WarpPlan::update (new end poses) + WarpPlan::apply (the warped
//                        positions of the plan's vertices: what a commit writes, and what
//                        live_positions() computes when a consumer asks)
//   Live/<group>/<k>     WarpPlan::update alone: the station's live step since issue 24
//                        (the display warps; the station sends the screws)
// group none (k = 1) is the two-hand update without symmetry (the float SIMD kernel).
// Ratios use CPU time (the build machine is shared with other builders), the median
// with --benchmark_repetitions.
// A unit sphere of 40,000 vertices (a Fibonacci lattice), radius 0.3, the hands at two
// generic points (no image of one near the other). After the run a table gives each
// group's time over the baseline's and the acceptance bound 1.2 k.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "twister/math/symmetry.hpp"
#include "twister/math/warp_plan.hpp"

namespace {

using twister::math::Frame;
using twister::math::PlanSymmetry;
using twister::math::SymmetryGroup;
using twister::math::SymmetryKind;
using twister::math::SymmetrySpec;
using twister::math::WarpMethod;
using twister::math::WarpPlan;

constexpr std::size_t kVertices = 40'000;
constexpr double kRadius = 0.3;

Frame turned(glm::dvec3 origin, glm::dvec3 axis, double angle, glm::dvec3 move) {
  const glm::dquat q = glm::angleAxis(angle, glm::normalize(axis));
  return Frame{origin + move, q * glm::dvec3(1, 0, 0), q * glm::dvec3(0, 1, 0),
               q * glm::dvec3(0, 0, 1)};
}

struct Scene {
  std::vector<float> x, y, z, ox, oy, oz, sx, sy, sz;
  std::vector<std::uint32_t> indices;
  std::vector<float> w1, w2;
  std::vector<std::uint64_t> balls;
  std::vector<float> weights;
  PlanSymmetry symmetry;
  std::unique_ptr<WarpPlan> plan;
  std::array<Frame, 2> start, end, end_b;
};

std::unique_ptr<Scene> make_scene(const SymmetrySpec& spec) {
  auto s = std::make_unique<Scene>();
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < kVertices; ++i) {
    const double zz = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / kVertices;
    const double rr = std::sqrt(1.0 - zz * zz);
    const double th = golden * static_cast<double>(i);
    s->x.push_back(static_cast<float>(rr * std::cos(th)));
    s->y.push_back(static_cast<float>(rr * std::sin(th)));
    s->z.push_back(static_cast<float>(zz));
  }
  s->ox = s->x;
  s->oy = s->y;
  s->oz = s->z;
  for (auto* v : {&s->sx, &s->sy, &s->sz, &s->w1, &s->w2}) v->resize(kVertices);
  s->indices.resize(kVertices);
  s->symmetry.start = twister::math::VertexColumns{s->sx, s->sy, s->sz};
  s->balls.resize(twister::math::SymmetricFloat::words_for(kVertices));
  s->symmetry.balls = s->balls;
  s->weights.resize(twister::math::SymmetricFloat::weights_for(kVertices));
  s->symmetry.weights = s->weights;
  s->plan = std::make_unique<WarpPlan>(
      twister::math::WarpPlanStorage{s->indices, s->w1, s->w2, &s->symmetry});
  // Two generic grab points on the sphere, 0.25 apart (each ball holds the other).
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.31, 0.52, 0.79));
  const glm::dvec3 b = glm::normalize(a + glm::dvec3(0.2, -0.1, 0.12));
  s->start = {turned(a, {0, 0, 1}, 0.0, {}), turned(b, {0, 0, 1}, 0.0, {})};
  s->end = {turned(a, {1, 2, 3}, 0.6, {0.03, 0.02, -0.01}),
            turned(b, {3, -1, 2}, -0.5, {-0.02, 0.01, 0.03})};
  s->end_b = {turned(a, {1, 2, 3}, 0.61, {0.03, 0.021, -0.01}),
              turned(b, {3, -1, 2}, -0.49, {-0.02, 0.011, 0.03})};
  SymmetryGroup group;
  if (!group.set(spec).ok()) std::abort();
  if (!s->plan->build({s->x, s->y, s->z}, s->start, kRadius, WarpMethod::twister, group).ok()) {
    std::abort();
  }
  return s;
}

void update(benchmark::State& state, SymmetrySpec spec, bool commit) {
  auto s = make_scene(spec);
  bool flip = false;
  for (auto _ : state) {
    const auto& end = flip ? s->end_b : s->end;
    flip = !flip;
    if (!s->plan->update(end).ok()) state.SkipWithError("update");
    if (commit && !s->plan->apply({s->x, s->y, s->z}, {s->ox, s->oy, s->oz}).ok()) {
      state.SkipWithError("apply");
    }
    benchmark::DoNotOptimize(s->ox.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = static_cast<double>(s->plan->indices().size());
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(s->plan->indices().size()));
}

// Collects each run's time per iteration for the ratio table.
class Collector : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.error_occurred) continue;
      // One run: its time; with --benchmark_repetitions: the median (it comes last).
      const bool median = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
      if (r.run_type == Run::RT_Iteration || median) {
        const std::string name = r.run_name.str();
        times[name] = r.GetAdjustedCPUTime();  // CPU: the machine is shared
        vertices[name] = r.counters.at("vertices").value;
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times;
  std::map<std::string, double> vertices;
};

struct Case {
  const char* name;
  SymmetrySpec spec;
};

}  // namespace

int main(int argc, char** argv) {
  using K = SymmetryKind;
  const Case cases[] = {
      {"none", {}},
      {"x", {K::mirrors, twister::math::kMirrorX, 0, 0}},
      {"xy", {K::mirrors, twister::math::kMirrorX | twister::math::kMirrorY, 0, 0}},
      {"xyz", {K::mirrors, 7, 0, 0}},
      {"rot3", {K::rotation, 0, 2, 3}},
      {"rot6", {K::rotation, 0, 2, 6}},
      {"rot6mirror", {K::rotation_mirror, 0, 2, 6}},
      {"rot12mirror", {K::rotation_mirror, 0, 2, 12}},
  };
  char name[64];
  std::vector<std::pair<std::string, std::size_t>> registered[2];  // live, commit
  for (const bool commit : {false, true}) {
    for (const Case& c : cases) {
      SymmetryGroup g;
      if (!g.set(c.spec).ok()) return 1;
      std::snprintf(name, sizeof name, "%s/%s/%zu", commit ? "Commit" : "Live", c.name, g.order());
      benchmark::RegisterBenchmark(name, update, c.spec, commit)
          ->Unit(commit ? benchmark::kMicrosecond : benchmark::kNanosecond);
      registered[commit ? 1 : 0].emplace_back(name, g.order());
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();
  for (const auto& rows : registered) {
    const auto base = collector.times.find(rows[0].first);
    if (base == collector.times.end()) continue;
    std::printf("\n%-26s %3s %9s %12s %10s %10s %s\n", "row", "k", "vertices", "time/base",
                "bound 1.2k", "per vertex", "");
    for (const auto& [n, k] : rows) {
      const auto t = collector.times.find(n);
      if (t == collector.times.end()) continue;
      const double ratio = t->second / base->second;
      const double per_vertex = ratio * collector.vertices[rows[0].first] / collector.vertices[n];
      std::printf("%-26s %3zu %9.0f %12.2f %10.2f %10.2f %s\n", n.c_str(), k, collector.vertices[n],
                  ratio, 1.2 * static_cast<double>(k), per_vertex,
                  ratio <= 1.2 * static_cast<double>(k) ? "within" : "OVER");
    }
  }
  return 0;
}
