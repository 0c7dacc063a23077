#include "twister/math/symmetric_kernel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <limits>

#include "twister/math/warp_plan.hpp"  // fill_kernel_hand

namespace twister::math {

namespace {

void map(double (&v)[3], const glm::dmat3& g, double sign = 1.0) {
  const glm::dvec3 m = sign * (g * glm::dvec3(v[0], v[1], v[2]));
  v[0] = m.x;
  v[1] = m.y;
  v[2] = m.z;
}

}  // namespace

void conjugate_kernel_hand(KernelHand& h, const glm::dmat3& g) {
  // (gA) x (gB) = det(g) g (A x B): with D' = det(g) g D every term of the kernel's
  // displacement at P is g times the hand's displacement at g^-1 P (docs/math.md §11.7).
  map(h.axis, g, glm::determinant(g) < 0.0 ? -1.0 : 1.0);
  map(h.mid, g);
  map(h.chord, g);
  map(h.axis_x_chord, g);
  map(h.shift, g);
}

void SymmetricFloat::reset() {
  points_ = 0;
  slots_ = 0;
  room_ = false;
  stored_ = false;
  rebased_ = false;
  weights_ = {};
  ready_ = false;
  words_ = {};
}

void SymmetricFloat::begin(const SymmetricWarp& warp, std::span<std::uint64_t> words,
                           std::span<float> weights, std::size_t room) {
  reset();
  if (!warp.built()) return;
  points_ = warp.grab_point_count();
  const double r = warp.radius();
  radius_ = static_cast<float>(r);
  std::size_t squashes = 0;
  std::size_t images = 0;
  for (std::size_t k = 0; k < points_; ++k) {
    Grab& g = grabs_[k];
    const glm::dvec3 p = warp.grab_point(k);
    for (int c = 0; c < 3; ++c) {
      g.hi[c] = static_cast<float>(p[c]);
      g.lo[c] = static_cast<float>(p[c] - static_cast<double>(g.hi[c]));
    }
    // The squashes of §11.3: every other grab point inside the ball.
    g.first_squash = static_cast<std::uint16_t>(squashes);
    for (std::size_t j = 0; j < points_; ++j) {
      const glm::dvec3 oq = warp.grab_point(j) - p;
      const double s = glm::length(oq);
      if (j == k || !(s < r) || s <= 0.0) continue;
      float* q = &squash_[4 * squashes++];
      q[0] = static_cast<float>(oq.x / s);
      q[1] = static_cast<float>(oq.y / s);
      q[2] = static_cast<float>(oq.z / s);
      q[3] = static_cast<float>((r - s) / s);
    }
    g.squashes = static_cast<std::uint16_t>(squashes - g.first_squash);
    g.steep = false;
    for (std::size_t j = 0; j < points_; ++j) {
      g.steep = g.steep || (j != k && glm::length(warp.grab_point(j) - p) < kSteepFraction * r);
    }
    // The images whose grab point this is (several when it lies on a plane or the axis).
    g.first_image = static_cast<std::uint8_t>(images);
    for (std::size_t h = 0; h < warp.hand_count(); ++h) {
      for (std::size_t e = 0; e < warp.group().order(); ++e) {
        if (warp.grab_point_of(h, e) == k) {
          images_[images++] = static_cast<std::uint8_t>(h * SymmetryGroup::kMaxOrder + e);
        }
      }
    }
    g.image_count = static_cast<std::uint8_t>(images - g.first_image);
  }
  room_ = words.size() >= words_for(room);
  if (room_) {
    words_ = words;
    weights_ = weights;
  }
}

bool SymmetricFloat::reaches(const SymmetricWarp& warp, glm::dvec3 p) const {
  for (std::size_t k = 0; k < points_; ++k) {
    if (glm::length(p - warp.grab_point(k)) < warp.radius()) return true;
  }
  return false;
}

namespace {
// Cells per axis in a ball's bounding cube for the sort (4: 64 cells, Morton order).
constexpr int kCells = 4;
constexpr std::size_t kKeys = SymmetricWarp::kMaxGrabPoints * kCells * kCells * kCells;

std::uint32_t morton(int x, int y, int z) {
  std::uint32_t m = 0;
  for (int b = 0; b < 2; ++b) {
    m |= static_cast<std::uint32_t>(((x >> b) & 1) | (((y >> b) & 1) << 1) | (((z >> b) & 1) << 2))
         << (3 * b);
  }
  return m;
}
}  // namespace

std::uint64_t SymmetricFloat::balls_of(const SymmetricWarp& warp, glm::dvec3 p,
                                       std::uint32_t& key) const {
  std::uint64_t mask = 0;
  const double r = warp.radius();
  key = 0;
  for (std::size_t k = 0; k < points_; ++k) {
    const glm::dvec3 v = p - warp.grab_point(k);
    if (!(glm::length(v) < r)) continue;
    if (mask == 0) {
      int c[3];
      for (int a = 0; a < 3; ++a) {
        c[a] = std::clamp(static_cast<int>(std::floor((v[a] / r + 1.0) * 0.5 * kCells)), 0,
                          kCells - 1);
      }
      key = static_cast<std::uint32_t>(k * kCells * kCells * kCells) + morton(c[0], c[1], c[2]);
    }
    mask |= std::uint64_t{1} << k;
  }
  return mask;
}

void SymmetricFloat::finish(const SymmetricWarp& warp, VertexColumns start,
                            std::span<const std::uint32_t> indices) {
  if (!room_ || indices.size() >= (std::size_t{1} << 31)) return;
  const std::size_t slots = indices.size();
  slots_ = slots;
  // A counting sort by key: the key of each slot in the high half of its word, then each
  // slot placed at its sorted position in the low half.
  std::array<std::uint32_t, kKeys> next{};
  for (std::size_t s = 0; s < slots; ++s) {
    std::uint32_t key = 0;
    (void)balls_of(warp, {start.x[s], start.y[s], start.z[s]}, key);
    words_[s] = std::uint64_t{key} << 32;
    ++next[key];
  }
  std::uint32_t sum = 0;
  for (std::uint32_t& n : next) {
    const std::uint32_t c = n;
    n = sum;
    sum += c;
  }
  for (std::size_t s = 0; s < slots; ++s) {
    const std::uint32_t pos = next[words_[s] >> 32]++;
    words_[pos] = (words_[pos] & ~std::uint64_t{0xffffffff}) | s;
  }
  for (std::size_t i = 0; i < slots; ++i) {
    const std::uint64_t s = words_[i] & 0xffffffffu;
    words_[i] = (s << 32) | indices[s];
  }
  // The chain-start columns into the sorted order, in place, cycle by cycle (bit 63
  // marks a position done): position i takes slot(i)'s.
  constexpr std::uint64_t kDone = std::uint64_t{1} << 63;
  for (std::size_t i = 0; i < slots; ++i) {
    if ((words_[i] & kDone) != 0) continue;
    const float tx = start.x[i], ty = start.y[i], tz = start.z[i];
    std::size_t at = i;
    for (;;) {
      words_[at] |= kDone;
      const auto from = static_cast<std::size_t>((words_[at] & ~kDone) >> 32);
      if (from == i) {
        start.x[at] = tx;
        start.y[at] = ty;
        start.z[at] = tz;
        break;
      }
      start.x[at] = start.x[from];
      start.y[at] = start.y[from];
      start.z[at] = start.z[from];
      at = from;
    }
  }
  for (std::size_t i = 0; i < slots; ++i) words_[i] &= ~kDone;
  // Each chunk's balls.
  const std::size_t chunks = (slots + kSortChunk - 1) / kSortChunk;
  for (std::size_t c = 0; c < chunks; ++c) {
    std::uint64_t mask = 0;
    for (std::size_t i = c * kSortChunk; i < std::min(slots, (c + 1) * kSortChunk); ++i) {
      std::uint32_t key = 0;
      mask |= balls_of(warp, {start.x[i], start.y[i], start.z[i]}, key);
    }
    words_[slots + c] = mask;
  }
  store_weights(warp, start);
  ready_ = true;
}

void SymmetricFloat::image_hand(const SymmetricWarp& warp, std::size_t i, KernelHand& out,
                                float& share) const {
  const std::size_t h = images_[i] / SymmetryGroup::kMaxOrder;
  const std::size_t e = images_[i] % SymmetryGroup::kMaxOrder;
  fill_kernel_hand(out, warp.screw(h), warp.start_frame(h), warp.end_frame(h), warp.method());
  if (e != 0) conjugate_kernel_hand(out, warp.group().element(e));
  share = 1.0f / static_cast<float>(warp.stabiliser_size(h));
}

void SymmetricFloat::fill_images(const SymmetricWarp& warp,
                                 std::array<PreparedHand, kMaxImages>& out,
                                 std::array<float, kMaxImages>& share) const {
  for (std::size_t i = 0; i < image_count(); ++i) {
    KernelHand hand;
    image_hand(warp, i, hand, share[i]);
    prepare_hand(hand, out[i]);
  }
}

// Each chunk's weights for each ball reaching it, once per grab, when they fit.
void SymmetricFloat::store_weights(const SymmetricWarp& warp, ConstVertexColumns start) {
  const std::size_t chunks = (slots_ + kSortChunk - 1) / kSortChunk;
  std::size_t need = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    need += kSortChunk * static_cast<std::size_t>(std::popcount(words_[slots_ + c]));
  }
  if (need > weights_.size()) return;
  std::size_t at = 0;
  for (std::size_t base = 0, c = 0; base < slots_; base += kSortChunk, ++c) {
    const std::size_t n = std::min(kSortChunk, slots_ - base);
    std::uint64_t balls = words_[slots_ + c];
    while (balls != 0) {
      const auto k = static_cast<std::size_t>(std::countr_zero(balls));
      balls &= balls - 1;
      weigh(warp, k, start.x.data() + base, start.y.data() + base, start.z.data() + base,
            weights_.data() + at, n, true);
      at += kSortChunk;
    }
  }
  stored_ = true;
}

void SymmetricFloat::weigh(const SymmetricWarp& warp, std::size_t k, const float* x, const float* y,
                           const float* z, float* w, std::size_t n, bool exact) const {
  const Grab& g = grabs_[k];
  if (exact || g.steep) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto v = static_cast<float>(warp.weight(k, {x[i], y[i], z[i]}));
      // As the float weights: none below 2^-32 (its sine's cube would underflow).
      w[i] = v > 0x1p-32f ? v : 0.0f;
    }
    return;
  }
  image_weights_simd(DecaySpan{x, y, z, w, n}, g.hi, g.lo,
                     &squash_[std::size_t{4} * g.first_squash], g.squashes, radius_);
}

void SymmetricFloat::apply(const SymmetricWarp& warp, ConstVertexColumns start,
                           ConstVertexColumns rest, VertexColumns out) const {
  std::array<PreparedHand, kMaxImages> hands;
  std::array<float, kMaxImages> share;
  fill_images(warp, hands, share);
  const std::uint64_t* __restrict order = words_.data();
  const float* __restrict rx = rest.x.data();
  const float* __restrict ry = rest.y.data();
  const float* __restrict rz = rest.z.data();
  float* __restrict ox = out.x.data();
  float* __restrict oy = out.y.data();
  float* __restrict oz = out.z.data();
  float q[3][kSortChunk];
  float d[3][kSortChunk];
  float computed[kSortChunk];
  std::size_t at = 0;
  for (std::size_t base = 0, chunk = 0; base < slots_; base += kSortChunk, ++chunk) {
    const std::size_t n = std::min(kSortChunk, slots_ - base);
    // Where the points are now: their chain-start positions (sorted, consecutive) until
    // the plan is rebased; after a clutch step, the rest columns (the previous step's).
    const float* px = start.x.data() + base;
    const float* py = start.y.data() + base;
    const float* pz = start.z.data() + base;
    const float* qx = px;
    const float* qy = py;
    const float* qz = pz;
    if (rebased_) {
      for (std::size_t i = 0; i < n; ++i) {
        const auto v = static_cast<std::uint32_t>(order[base + i]);
        q[0][i] = rx[v];
        q[1][i] = ry[v];
        q[2][i] = rz[v];
      }
      qx = q[0];
      qy = q[1];
      qz = q[2];
    }
    // The warped positions accumulate onto the current ones.
    std::memcpy(d[0], qx, n * sizeof(float));
    std::memcpy(d[1], qy, n * sizeof(float));
    std::memcpy(d[2], qz, n * sizeof(float));
    std::uint64_t balls = order[slots_ + chunk];
    while (balls != 0) {
      const auto k = static_cast<std::size_t>(std::countr_zero(balls));
      balls &= balls - 1;
      const float* w = weights_.data() + at;
      if (stored_) {
        at += kSortChunk;
      } else {
        weigh(warp, k, px, py, pz, computed, n, false);
        w = computed;
      }
      const Grab& g = grabs_[k];
      for (std::size_t i = g.first_image; i < std::size_t{g.first_image} + g.image_count; ++i) {
        add_displacement_simd(hands[i], share[i],
                              DisplacementSpan{qx, qy, qz, w, d[0], d[1], d[2], n});
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto v = static_cast<std::uint32_t>(order[base + i]);
      ox[v] = d[0][i];
      oy[v] = d[1][i];
      oz[v] = d[2][i];
    }
  }
}

void SymmetricFloat::warp_points(const SymmetricWarp& warp, const float* x, const float* y,
                                 const float* z, float* out_x, float* out_y, float* out_z,
                                 std::size_t n) const {
  n = std::min(n, kImageChunk);
  std::array<PreparedHand, kMaxImages> hands;
  std::array<float, kMaxImages> share;
  fill_images(warp, hands, share);
  float w[kImageChunk];
  for (std::size_t i = 0; i < n; ++i) {
    out_x[i] = 0.0f;
    out_y[i] = 0.0f;
    out_z[i] = 0.0f;
  }
  for (std::size_t k = 0; k < points_; ++k) {
    const Grab& g = grabs_[k];
    weigh(warp, k, x, y, z, w, n, true);  // double weights: error_bound's 2^-18
    // A ball that reaches none of the points (their weights exactly 0).
    float most = 0.0f;
    for (std::size_t i = 0; i < n; ++i) most = std::max(most, w[i]);
    if (!(most > 0.0f)) continue;
    for (std::size_t i = g.first_image; i < std::size_t{g.first_image} + g.image_count; ++i) {
      add_displacement_simd(hands[i], share[i],
                            DisplacementSpan{x, y, z, w, out_x, out_y, out_z, n});
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    out_x[i] += x[i];
    out_y[i] += y[i];
    out_z[i] += z[i];
  }
}

// docs/refinement.md "The float filter" for the plain plan (WarpPlan::float_error_bound),
// summed over every image of every hand (an image's kernel constants have the hand's
// magnitudes: g is orthogonal), with the weights in double (warp_points) so that their
// error is the float rounding, inside the plain bound's 2^-18, and the Lipschitz term's
// stretch from the closest two grab points.
double SymmetricFloat::error_bound(const SymmetricWarp& warp, double extent_m) const {
  if (!warp.built()) return std::numeric_limits<double>::infinity();
  constexpr double kWeight = 0x1p-18;
  constexpr double kKernel = 0x1p-16;
  constexpr double kRoot3 = 1.7320508075688772;
  const double r = warp.radius();
  double closest = r;
  for (std::size_t k = 0; k < points_; ++k) {
    for (std::size_t j = 0; j < k; ++j) {
      closest = std::min(closest, glm::length(warp.grab_point(k) - warp.grab_point(j)));
    }
  }
  const double stretch = closest > 0.0 && closest < r ? r / closest : 1.0;
  const auto images = static_cast<double>(warp.group().order());
  double bound = 0x1p-23 * kRoot3 * extent_m;
  double lipschitz = 1.0;
  for (std::size_t h = 0; h < warp.hand_count(); ++h) {
    KernelHand k;
    fill_kernel_hand(k, warp.screw(h), warp.start_frame(h), warp.end_frame(h), warp.method());
    const glm::dvec3 mid(k.mid[0], k.mid[1], k.mid[2]);
    const double kx =
        std::abs(k.cot_half) * glm::length(glm::dvec3(k.chord[0], k.chord[1], k.chord[2]));
    const double shift = glm::length(glm::dvec3(k.shift[0], k.shift[1], k.shift[2]));
    const double v = r + glm::length(warp.start_frame(h).origin - mid);
    const double magnitude = kRoot3 * extent_m + glm::length(mid) + kx + shift + 2 * v;
    const double slope = 2.0 * std::abs(k.half_angle) * (2.0 * v + kx) + shift;
    bound += images * (kKernel * magnitude + kWeight * slope);
    lipschitz += images * (4.0 + slope * 0.5 * 3.14159265358979324 / r * stretch);
  }
  return bound + 0x1p-23 * kRoot3 * extent_m * lipschitz;
}

}  // namespace twister::math
