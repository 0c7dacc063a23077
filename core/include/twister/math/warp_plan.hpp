// WarpPlan: one grab's warp of a vertex set, built once per grab into caller-owned
// fixed storage (docs/math.md §4-§6, §8).
//
//   build(rest, start frames, radius, method)  once per grab: selects the influenced
//                                              vertices and their decay weights
//   update(end frames)                         per tracker update: screw parameters
//   update_turns(end frames, long turns)       the same with each hand's turn sense
//                                              given (turns past a half turn)
//   apply(rest, out)                           per update: warped positions of the
//                                              influenced vertices only (hot path)
//   rebase(new start frames)                   freeze: same vertices and weights,
//                                              new start poses
//
// The influenced vertices of both hands are kept as ONE ascending index list with
// two weight columns aligned to it (weight 0 = not influenced by that hand), so the
// two-hand kernel streams through contiguous float columns. Weights are the decay
// t of §4 with the squash rule of §5 (for scodef they are the same decay, used for
// display only). World frame, scene units; rest/out are float SoA columns.
// No heap allocation and no exceptions anywhere in this class.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/base/status.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/scodef.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/symmetric_kernel.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/vertex_columns.hpp"
#include "twister/math/warp_kernels.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::math {

inline constexpr std::size_t kMaxHands = 2;
// The start or end frames of a plan's hands, in plan order.
using PlanFrames = InlineVector<Frame, kMaxHands>;
// Two grab points closer than this fraction of the radius count as the same point.
inline constexpr double kCoincidentGrabFraction = 1e-9;

// Caller-owned storage of a plan: one entry per influenced vertex in each span
// (capacity = the smallest span).
// The kernel form of one hand's screw for `method` (twister or rottran): the
// constants the warp kernels and the display's vertex shader evaluate per vertex.
void fill_kernel_hand(KernelHand& h, const Screw& s, const Frame& start, const Frame& end,
                      WarpMethod method);

// A plan's storage for symmetric strokes (docs/math.md §11): the symmetrised warp,
// and each plan vertex's chain-start position (the argument of its weights through a
// clutch chain: the symmetric weights are too many to store per vertex; each column at
// least the plan's capacity). Without it a plan builds only under the trivial group.
// `balls` (optional, SymmetricFloat::words_for(the plan's capacity) words): the plan's
// vertices sorted by the balls that hold them, for the float path (§11.7); without it
// (or too small) apply() evaluates the warp in double. `weights` (optional,
// SymmetricFloat::weights_for(capacity) floats): their weights, kept for the stroke
// (without: recomputed at each apply).
struct PlanSymmetry {
  SymmetricWarp warp{};
  VertexColumns start{};
  std::span<std::uint64_t> balls{};
  std::span<float> weights{};
  SymmetricFloat fast{};
};

struct WarpPlanStorage {
  std::span<std::uint32_t> indices;
  std::span<float> weights1;
  std::span<float> weights2;
  PlanSymmetry* symmetry = nullptr;  // optional: symmetric strokes
};

class WarpPlan {
 public:
  explicit WarpPlan(WarpPlanStorage storage);

  // Starts a grab. `start` holds 1 or 2 orthonormal frames (hand 1, hand 2).
  // invalid_argument: 0 or >2 frames, a frame not orthonormal or not finite,
  //   radius <= 0 or not finite, rest columns of unequal length or more than
  //   2^32-1 vertices, or the two grab points coincide (|OQ| ~ 0: squash undefined).
  // resource_exhausted: more influenced vertices than the storage holds.
  // failed_precondition: scodef constraint system singular.
  // On error the plan is empty (no hands) and apply() does nothing.
  Status build(ConstVertexColumns rest, std::span<const Frame> start, double radius,
               WarpMethod method);
  // The same under a symmetry group (docs/math.md §11). The trivial group is exactly
  // build() above. Otherwise the plan's vertices are those within the radius of some
  // grab point (every image of every hand), weights1/weights2 are each hand's own
  // (identity image) weight, for the display; apply() evaluates the symmetrised warp
  // in float, one kernel hand per image (SymmetricFloat, §11.7) with the simd kernel and
  // PlanSymmetry::balls, else per vertex in double (math::SymmetricWarp, the scalar
  // reference); warp_point() in double. scodef (§11.8): the vertices some basis of some
  // image reaches, warped per vertex in double (no float path, as without a group).
  // failed_precondition: no PlanSymmetry storage, or a singular scodef system;
  // invalid_argument also for a hand on another hand's image; errors as build otherwise.
  Status build(ConstVertexColumns rest, std::span<const Frame> start, double radius,
               WarpMethod method, const SymmetryGroup& group);

  // New end poses (same count as build). Keeps the previous update's axis sense at
  // a half turn (§2). invalid_argument: wrong count or frame not orthonormal;
  // failed_precondition: not built. On error the previous update stays in force.
  Status update(std::span<const Frame> end);

  // New end poses with each hand's screw chosen by the caller (docs/unwrap.md): hand
  // i's screw is the minimal screw of its poses (computed from the poses alone, with
  // no half-turn sense carried over: exactly what a replay of the poses computes), or
  // that screw the long way round (long_way_round(), angle past pi) when bit i of
  // `long_turns` is set. Errors as update(); on error the previous update stays.
  Status update_turns(std::span<const Frame> end, std::uint8_t long_turns);

  // Writes the warped position of every influenced vertex into `out` (same index);
  // other entries of `out` are not touched. `rest` must be the columns given to
  // build (same size); `out` must not alias `rest`.
  // invalid_argument: column sizes differ from build; failed_precondition: not built.
  Status apply(ConstVertexColumns rest, VertexColumns out) const;

  // Freeze (§8): keeps the selection and weights, restarts from `start` (usually the
  // current end poses) with an identity update. Errors as update(), plus
  // failed_precondition for a singular scodef system.
  Status rebase(std::span<const Frame> start);

  // Forgets the grab (no hands).
  void reset();

  // The warp of one point in double precision, with its weight computed from p as
  // a rest position (adaptive refinement, CLI checks). Identity when not built.
  glm::dvec3 warp_point(glm::dvec3 p) const;

  // warp_point for n points in single precision (weights from a float polynomial decay,
  // then the simd kernel): the adaptive refinement's filter. False (nothing written)
  // for scodef or when not built. n <= kFloatChunk.
  static constexpr std::size_t kFloatChunk = 256;
  bool warp_points_float(const float* x, const float* y, const float* z, float* out_x, float* out_y,
                         float* out_z, std::size_t n) const;
  // A bound on |warp_points_float(p) - warp_point(p)| (metres) for every point with
  // |p| <= extent_m (each coordinate; docs/refinement.md "The float filter").
  double float_error_bound(double extent_m) const;

  // Kernel used by apply() (default simd); scalar is the reference.
  void set_kernel(KernelKind kind) { kernel_ = kind; }
  KernelKind kernel() const { return kernel_; }

  bool built() const { return hands_ > 0; }
  std::size_t hand_count() const { return hands_; }
  std::size_t capacity() const { return indices_.size(); }
  // Built under a non-trivial group (build with a group).
  bool symmetric() const { return symmetry_ != nullptr && symmetry_->warp.built(); }
  // The group's parameters (kind none unless symmetric()).
  SymmetrySpec symmetry() const {
    return symmetric() ? symmetry_->warp.group().spec() : SymmetrySpec{};
  }
  // The symmetrised warp (meaningful while symmetric()).
  const SymmetricWarp* symmetric_warp() const { return symmetric() ? &symmetry_->warp : nullptr; }
  double radius() const { return radius_; }
  WarpMethod method() const { return method_; }
  // Union of influenced vertex indices, ascending.
  std::span<const std::uint32_t> indices() const { return {indices_.data(), count_}; }
  // Weights of `hand` (0 or 1) aligned with indices(); 0 where the hand has none.
  std::span<const float> weights(std::size_t hand) const;
  // Number of vertices with a non-zero weight for `hand`.
  std::size_t influenced_count(std::size_t hand) const;
  const Frame& start_frame(std::size_t hand) const { return start_[hand]; }
  const Frame& end_frame(std::size_t hand) const { return end_[hand]; }
  // The screw of `hand` for the last update (identity right after build).
  const Screw& screw(std::size_t hand) const { return screws_[hand]; }
  // Bit i: plan hand i's screw goes the long way round (last update_turns()).
  std::uint8_t long_turns() const { return long_turns_; }

 private:
  Status check_frames(std::span<const Frame> frames) const;
  // update() (keep_sense: the half-turn hint of §2) and update_turns().
  Status set_end(std::span<const Frame> end, bool keep_sense, std::uint8_t long_turns);
  void set_kernel_hands();
  void take(std::size_t i, double w1, double w2);
  void finish_build(std::size_t rest_size);
  double weight_of(std::size_t hand, glm::dvec3 p) const;
  Status build_symmetric(ConstVertexColumns rest, std::span<const Frame> start, double radius,
                         WarpMethod method, const SymmetryGroup& group);
  void apply_symmetric(ConstVertexColumns rest, VertexColumns out) const;

  // Trimmed to the capacity (the shortest of the three).
  std::span<std::uint32_t> indices_;
  std::span<float> weights1_;
  std::span<float> weights2_;
  PlanSymmetry* symmetry_ = nullptr;
  std::size_t count_ = 0;
  std::size_t rest_size_ = 0;
  std::array<std::size_t, kMaxHands> hand_counts_{};
  std::size_t hands_ = 0;
  std::uint8_t long_turns_ = 0;
  bool dense_ = false;  // indices are first, first+1, ... (no gather needed)
  double radius_ = 1.0;
  WarpMethod method_ = WarpMethod::twister;
  KernelKind kernel_ = KernelKind::simd;
  std::array<Frame, kMaxHands> start_{};
  std::array<Frame, kMaxHands> end_{};
  std::array<Screw, kMaxHands> screws_{};
  std::array<KernelHand, kMaxHands> kernel_hands_{};
  ScodefSystem scodef_{};
};

namespace internal {
template <std::size_t N>
struct WarpPlanArrays {
  std::array<std::uint32_t, N> index_storage{};
  std::array<float, N> weight1_storage{};
  std::array<float, N> weight2_storage{};
};
}  // namespace internal

// A plan owning storage for N influenced vertices (about 12*N bytes: place large
// ones in static storage or the start-up arena, not on the stack).
template <std::size_t N>
class WarpPlanWithStorage : private internal::WarpPlanArrays<N>, public WarpPlan {
 public:
  WarpPlanWithStorage()
      : WarpPlan(
            WarpPlanStorage{this->index_storage, this->weight1_storage, this->weight2_storage}) {}
  WarpPlanWithStorage(const WarpPlanWithStorage&) = delete;
  WarpPlanWithStorage& operator=(const WarpPlanWithStorage&) = delete;
};

}  // namespace twister::math
