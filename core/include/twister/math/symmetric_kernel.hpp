// The symmetrised warp of docs/math.md §11 in single precision (§11.7): every image g of
// every hand h is one more kernel hand, the conjugated screw g S_h g^-1, with the float
// weight of its grab point g.O_h (the several-point squash of §11.3, only the grab points
// inside its ball). A plan's vertices are sorted into the balls that reach them once per
// grab (a bit set per grab point over the plan's slots, caller storage), so an update
// costs about one kernel hand per (vertex, ball reaching it).
// No heap, no exceptions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <span>

#include "twister/math/symmetry.hpp"
#include "twister/math/vertex_columns.hpp"
#include "twister/math/warp_kernels.hpp"

namespace twister::math {

// The kernel form of hand `hand`'s image under `g` (orthogonal): g S g^-1, i.e. the axis
// mapped and turned over by det g, every point and vector mapped by g.
void conjugate_kernel_hand(KernelHand& h, const glm::dmat3& g);

class SymmetricFloat {
 public:
  static constexpr std::size_t kMaxImages = SymmetricWarp::kMaxGrabPoints;
  // A ball with another grab point closer than this fraction of the radius has a squash
  // stretch above ~1/kSteepFraction, which multiplies the float weight's rounding: its
  // weights are computed in double (§11.7).
  static constexpr double kSteepFraction = 1.0 / 64.0;
  // Plan slots per chunk of the sorted order (each chunk runs the kernel of every ball
  // that reaches one of its slots, over all its slots).
  static constexpr std::size_t kSortChunk = 64;
  // Words of storage a plan of `capacity` vertices needs (about 8 bytes a vertex): the
  // sorted order of the slots, and per chunk the set of balls that reach it.
  static constexpr std::size_t words_for(std::size_t capacity) {
    return capacity + (capacity + kSortChunk - 1) / kSortChunk;
  }
  // Floats of weight storage that hold kWeightsPerSlot weights a plan vertex: each
  // chunk's weights for each ball reaching it, fixed per grab (computed once in finish;
  // beyond that room apply() computes them per update, slower).
  static constexpr std::size_t kWeightsPerSlot = 4;
  static constexpr std::size_t weights_for(std::size_t capacity) {
    return kWeightsPerSlot * (capacity + kSortChunk);
  }

  // After warp.build(): the float constants of every grab point (hi/lo, its squashes),
  // and the storage for the order of up to `room` plan slots (too small: ready() stays
  // false and the caller keeps the double path; warp_points still works) and their
  // weights (optional).
  void begin(const SymmetricWarp& warp, std::span<std::uint64_t> words, std::span<float> weights,
             std::size_t room);
  // Whether some ball holds p (|p - P_k| < r): the plan's selection.
  bool reaches(const SymmetricWarp& warp, glm::dvec3 p) const;
  // After the plan's selection: sorts its `slots` slots (chain-start positions `start`)
  // by the ball that first holds them and by cell within it, so that a chunk of
  // consecutive sorted slots lies in a small region, and records each chunk's balls.
  // The chain-start columns are permuted into the sorted order (vertex(i) is sorted
  // position i's vertex).
  void finish(const SymmetricWarp& warp, VertexColumns start,
              std::span<const std::uint32_t> indices);
  // A clutch step: from now on the points move from the rest columns given to apply
  // (until then from their chain-start positions, which the rest columns equal).
  void rebased() { rebased_ = true; }
  // The vertex at sorted position i (ready()).
  std::uint32_t vertex(std::size_t i) const { return static_cast<std::uint32_t>(words_[i]); }
  void reset();
  // The sorted order built (begin with enough words, finish).
  bool ready() const { return ready_; }

  // The plan's warp (WarpPlan::apply under a group): out[v] = F(p_i, q_v) for every
  // sorted position i, v = vertex(i), p_i = start[i] (chain start: the weights),
  // q_v = rest[v] (p_i itself until rebased()).
  void apply(const SymmetricWarp& warp, ConstVertexColumns start, ConstVertexColumns rest,
             VertexColumns out) const;
  // F(p) for n <= kImageChunk points (weights and motion from p): the refiner's batch
  // (the weights in double, the images' motion in the float kernel).
  void warp_points(const SymmetricWarp& warp, const float* x, const float* y, const float* z,
                   float* out_x, float* out_y, float* out_z, std::size_t n) const;
  // A bound on |warp_points(p) - warp.warp_point(p)| for |p| <= extent_m per coordinate.
  double error_bound(const SymmetricWarp& warp, double extent_m) const;

  // For a display that sums the images on the GPU (twister-bridge's vertex shader,
  // docs/math.md §11.7): the images in apply()'s order, image i's kernel hand for the
  // current screws (g S_h g^-1) and its share 1/|G_h|, and ball k's images
  // [ball_first_image(k), ball_first_image(k) + ball_image_count(k)).
  std::size_t image_count() const {
    return points_ == 0
               ? 0
               : std::size_t{grabs_[points_ - 1].first_image} + grabs_[points_ - 1].image_count;
  }
  void image_hand(const SymmetricWarp& warp, std::size_t i, KernelHand& out, float& share) const;
  std::size_t ball_first_image(std::size_t k) const { return grabs_[k].first_image; }
  std::size_t ball_image_count(std::size_t k) const { return grabs_[k].image_count; }
  // Every weight apply() uses (ready()): for each sorted chunk (positions base .. base +
  // n - 1, vertex(base + i)) and each ball k reaching it, visit(base, k, w, n) with w its
  // n weights, kept or computed exactly as apply() computes them. No heap.
  template <class Visit>
  void visit_weights(const SymmetricWarp& warp, ConstVertexColumns start, Visit&& visit) const {
    float computed[kSortChunk];
    std::size_t at = 0;
    for (std::size_t base = 0, chunk = 0; base < slots_; base += kSortChunk, ++chunk) {
      const std::size_t n = slots_ - base < kSortChunk ? slots_ - base : kSortChunk;
      std::uint64_t balls = words_[slots_ + chunk];
      for (std::size_t k = 0; balls != 0; ++k, balls >>= 1) {
        if ((balls & 1u) == 0) continue;
        const float* w = weights_.data() + at;
        if (stored_) {
          at += kSortChunk;
        } else {
          weigh(warp, k, start.x.data() + base, start.y.data() + base, start.z.data() + base,
                computed, n, false);
          w = computed;
        }
        visit(base, k, w, n);
      }
    }
  }
  // Ball k's weights at n <= kSortChunk points as apply() computes them when they are
  // not kept (float, or double where the ball is steep).
  void weights_at(const SymmetricWarp& warp, std::size_t k, const float* x, const float* y,
                  const float* z, float* w, std::size_t n) const {
    weigh(warp, k, x, y, z, w, n, false);
  }

 private:
  struct Grab {
    float hi[3];
    float lo[3];
    std::uint16_t first_squash;  // into squash_ (4 floats each)
    std::uint16_t squashes;
    std::uint8_t first_image;  // into images_
    std::uint8_t image_count;
    bool steep;  // another grab point within kSteepFraction r: weights in double
  };
  // Balls holding p (bit k: grab point k), and the sort key of p (first ball, cell).
  std::uint64_t balls_of(const SymmetricWarp& warp, glm::dvec3 p, std::uint32_t& key) const;
  // The kernel hands of every image (g, h) for the current screws, ordered as images_.
  void fill_images(const SymmetricWarp& warp, std::array<PreparedHand, kMaxImages>& out,
                   std::array<float, kMaxImages>& share) const;
  void store_weights(const SymmetricWarp& warp, ConstVertexColumns start);
  // Grab point k's weights of n points: float (simd) unless the ball is steep or
  // `exact`, then double (SymmetricWarp::weight) rounded to float.
  void weigh(const SymmetricWarp& warp, std::size_t k, const float* x, const float* y,
             const float* z, float* w, std::size_t n, bool exact) const;

  std::array<Grab, SymmetricWarp::kMaxGrabPoints> grabs_{};
  std::array<float, 4 * SymmetricWarp::kMaxGrabPoints * SymmetricWarp::kMaxGrabPoints> squash_{};
  // Image i: hand images_[i] / kMaxOrder, element images_[i] % kMaxOrder; grouped by grab
  // point (each grab point's images contiguous, from its first_image).
  std::array<std::uint8_t, kMaxImages> images_{};
  // words_[i] (i < slots_): the plan slot at sorted position i (high 32 bits; its key
  // while sorting) and its vertex index (low 32); words_[slots_ + c]: the balls reaching
  // chunk c.
  std::span<std::uint64_t> words_{};
  std::span<float> weights_{};  // per chunk, per ball reaching it: kSortChunk weights
  bool stored_ = false;         // weights_ holds every chunk's weights
  bool rebased_ = false;
  std::size_t slots_ = 0;
  std::size_t points_ = 0;
  float radius_ = 1.0f;
  bool room_ = false;  // storage enough for this grab
  bool ready_ = false;
};

}  // namespace twister::math
