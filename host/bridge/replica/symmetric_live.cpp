// The replica's symmetric stroke for the display's shader (symmetric_live.hpp): the
// plan's own weights and images, rearranged per vertex.
#include <algorithm>
#include <atomic>

#include "replica_plan.hpp"
#include "scene_replica.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::bridge {
namespace {

using math::SymmetricFloat;

// One non-zero weight of ball `ball` at plan vertex `vertex`, with its gradient.
struct Found {
  std::uint32_t vertex;
  std::uint32_t ball;
  float w[4];  // weight, gradient x y z
};

// Ball k's weight gradients at the n points (x, y, z) of weights w (the plan's own
// weights, one-sided differences of step `h`): g[a][i]. Once per grab, the
// gradients cost three more weight evaluations a point (the shader's normals).
void gradients(const SymmetricFloat& fast, const math::SymmetricWarp& warp, std::size_t k,
               const float (&x)[3][SymmetricFloat::kSortChunk], const float* w, std::size_t n,
               float h, float (&g)[3][SymmetricFloat::kSortChunk]) {
  float p[3][SymmetricFloat::kSortChunk];
  float up[SymmetricFloat::kSortChunk];
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t b = 0; b < 3; ++b) std::copy_n(x[b], n, p[b]);
    for (std::size_t i = 0; i < n; ++i) p[a][i] = x[a][i] + h;
    fast.weights_at(warp, k, p[0], p[1], p[2], up, n);
    for (std::size_t i = 0; i < n; ++i) g[a][i] = (up[i] - w[i]) / h;
  }
}

void copy3(float (&to)[3], const double (&from)[3]) {
  for (std::size_t i = 0; i < 3; ++i) to[i] = static_cast<float>(from[i]);
}

// Collects the non-zero weights of each (chunk, ball) the plan visits, with their
// gradients; stops keeping them past kMaxSymmetricEntries (the CPU path draws those).
struct Collector {
  const SymmetricFloat& fast;
  const math::SymmetricWarp& warp;
  math::ConstVertexColumns start;
  float step;
  std::vector<Found> found;
  std::size_t total = 0;  // entries: found weights times their balls' images

  void operator()(std::size_t base, std::size_t k, const float* w, std::size_t count) {
    if (total > kMaxSymmetricEntries) return;
    // The points this ball moves (weight > 0), gathered.
    std::uint32_t slot[SymmetricFloat::kSortChunk];
    float at[3][SymmetricFloat::kSortChunk];
    float wk[SymmetricFloat::kSortChunk];
    std::size_t m = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (!(w[i] > 0.0F)) continue;
      slot[m] = static_cast<std::uint32_t>(base + i);
      at[0][m] = start.x[base + i];
      at[1][m] = start.y[base + i];
      at[2][m] = start.z[base + i];
      wk[m++] = w[i];
    }
    if (m == 0) return;
    float g[3][SymmetricFloat::kSortChunk];
    gradients(fast, warp, k, at, wk, m, step, g);
    for (std::size_t i = 0; i < m; ++i) {
      found.push_back({fast.vertex(slot[i]),
                       static_cast<std::uint32_t>(k),
                       {wk[i], g[0][i], g[1][i], g[2][i]}});
      total += fast.ball_image_count(k);
    }
  }
};

}  // namespace

void SceneReplica::build_symmetric_gpu() {
  SymmetricLive& gpu = live_.symmetric_gpu;
  gpu.ready = false;
  gpu.image_count = 0;
  // Unique across replicas, so a renderer never mistakes another replica's entries
  // for the ones it holds.
  static std::atomic<std::uint64_t> builds{0};
  gpu.version = ++builds;
  gpu.entries.clear();
  gpu.entry_image.clear();
  const std::size_t n = mesh_.vertex_count();
  gpu.spans.assign(2 * n, 0.0F);
  if (!plan_ || !plan_->plan || !plan_->plan->symmetric() || !plan_->symmetry ||
      plan_->plan->kernel() != math::KernelKind::simd) {
    return;
  }
  const math::PlanSymmetry& sym = *plan_->symmetry->plan_symmetry();
  const SymmetricFloat& fast = sym.fast;
  if (!fast.ready()) return;  // the plan runs the double path: so does the display
  const math::SymmetricWarp& warp = sym.warp;
  const math::ConstVertexColumns start{sym.start.x, sym.start.y, sym.start.z};
  Collector c{fast, warp, start, static_cast<float>(1e-3 * warp.radius()), {}, 0};
  fast.visit_weights(warp, start, c);
  const std::vector<Found>& found = c.found;
  const std::size_t total = c.total;
  if (total > kMaxSymmetricEntries) return;
  // Per vertex its entries in the order the plan sums them (balls in increasing order,
  // each ball's images in order): a vertex lies in one chunk, visited ball by ball.
  std::vector<std::uint32_t> next(n, 0);
  for (const Found& f : found) {
    next[f.vertex] += static_cast<std::uint32_t>(fast.ball_image_count(f.ball));
  }
  std::uint32_t sum = 0;
  for (std::size_t v = 0; v < n; ++v) {
    gpu.spans[2 * v] = static_cast<float>(sum);
    gpu.spans[2 * v + 1] = static_cast<float>(next[v]);
    const std::uint32_t count = next[v];
    next[v] = sum;
    sum += count;
  }
  gpu.entries.resize(4 * total);
  gpu.entry_image.resize(total);
  for (const Found& f : found) {
    const std::size_t first = fast.ball_first_image(f.ball);
    for (std::size_t i = 0; i < fast.ball_image_count(f.ball); ++i) {
      const std::uint32_t e = next[f.vertex]++;
      std::copy_n(f.w, 4, &gpu.entries[std::size_t{4} * e]);
      gpu.entry_image[e] = static_cast<std::uint8_t>(first + i);
    }
  }
  gpu.ready = true;
}

void SceneReplica::update_symmetric_images() {
  SymmetricLive& gpu = live_.symmetric_gpu;
  gpu.image_count = 0;
  if (!gpu.ready || !plan_ || !plan_->plan || !follow_hands()) return;
  const math::PlanSymmetry& sym = *plan_->symmetry->plan_symmetry();
  for (std::size_t i = 0; i < sym.fast.image_count(); ++i) {
    math::KernelHand k;
    SymmetricImageGpu& out = gpu.images[i];
    sym.fast.image_hand(sym.warp, i, k, out.share);
    copy3(out.axis, k.axis);
    copy3(out.mid, k.mid);
    copy3(out.chord, k.chord);
    copy3(out.axc, k.axis_x_chord);
    copy3(out.shift, k.shift);
    out.half = static_cast<float>(k.half_angle);
    out.cot = static_cast<float>(k.cot_half);
    out.pad0 = 0.0F;
    out.pad1 = 0.0F;
  }
  gpu.image_count = sym.fast.image_count();
}

}  // namespace twister::bridge
