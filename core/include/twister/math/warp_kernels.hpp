// Per-vertex warp kernels over dense float columns: the per-update hot path.
// Both kernels compute, per hand with decay weight t,
//   disp = sh*ch*(2 D x v + k X) + sh^2*(2 (D(D.v) - v) + k (D x X)) + t T,
//   v = P - M, sh = sin(t*a/2), ch = cos(t*a/2), k = cot(a/2),
// which is S(t)(P) - P for twister (T = dD) and rottran (M = O, k = 0, T = OO').
// `scalar` is the reference (double arithmetic, std::sin/cos, one vertex at a
// time); `simd` is single precision with polynomial sin/cos, auto-vectorised and
// dispatched at run time (AVX2+FMA where the CPU has them, baseline otherwise). A
// screw the long way round (a > pi, docs/unwrap.md) takes a variant of the simd loop
// with a range-reduced sin/cos; minimal screws keep the cheaper one.
#pragma once

#include <cstddef>
#include <cstdint>

namespace twister::math {

enum class KernelKind : std::uint8_t { scalar, simd };

// One hand's per-update parameters in kernel form (see above), world frame, in
// double; the simd kernel rounds them to float once per call.
struct KernelHand {
  double axis[3] = {0.0, 0.0, 1.0};          // D
  double mid[3] = {0.0, 0.0, 0.0};           // M (O for rottran)
  double chord[3] = {0.0, 0.0, 0.0};         // X (0 for rottran)
  double axis_x_chord[3] = {0.0, 0.0, 0.0};  // D x X
  double shift[3] = {0.0, 0.0, 0.0};         // T: dD (twister), OO' (rottran, pure)
  double half_angle = 0.0;                   // a/2 in [0, pi/2]; up to pi the long way round
  double cot_half = 0.0;                     // k
};

// Dense columns: n rest positions with their weights in, n warped positions out.
// Output columns must not alias the inputs. w2 is ignored by the one-hand kernels.
struct KernelSpan {
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  const float* w1 = nullptr;
  const float* w2 = nullptr;
  float* out_x = nullptr;
  float* out_y = nullptr;
  float* out_z = nullptr;
  std::size_t n = 0;
};

void warp_one_scalar(const KernelHand& h1, const KernelSpan& s);
void warp_two_scalar(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s);
void warp_one_simd(const KernelHand& h1, const KernelSpan& s);
// The decay weight of one hand (docs/math.md §4-§5) for n points in single precision:
// squashed by `stretch` along the unit `unit` where (p - grab).unit > 0 (0: no squash),
// then cos^2(pi/2 d / radius) inside the radius, 0 outside (polynomial cos). The
// adaptive refinement's float filter (WarpPlan::warp_points_float).
struct DecaySpan {
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  float* w = nullptr;
  std::size_t n = 0;
};
void decay_weights_simd(const DecaySpan& s, const float grab[3], const float unit[3], float stretch,
                        float radius);
void warp_two_simd(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s);

// The symmetric float path (docs/math.md §11.7). The weight of one grab point for n
// points (n <= kImageChunk) in single precision: the grab point as hi + lo floats (so
// that p - grab is exact to float rounding of the difference, not of the coordinates),
// `count` squashes of §11.3 as {ux, uy, uz, stretch} (unit towards the other grab
// point, (r - s) / s), w = cos^2(pi/2 min(d/r, 1)) with d the largest squashed distance
// (the min over the pairwise weights), 0 outside the radius.
inline constexpr std::size_t kImageChunk = 256;
void image_weights_simd(const DecaySpan& s, const float grab_hi[3], const float grab_lo[3],
                        const float* squash, std::size_t count, float radius);
// d += share * (the displacement of hand h at weight w): one image-hand (a conjugated
// screw in kernel form) over n gathered points, accumulated into d.
struct DisplacementSpan {
  const float* x = nullptr;
  const float* y = nullptr;
  const float* z = nullptr;
  const float* w = nullptr;
  float* dx = nullptr;
  float* dy = nullptr;
  float* dz = nullptr;
  std::size_t n = 0;
};
// A hand's float constants, prepared once per update (the simd kernel's own form).
struct PreparedHand {
  float c[13] = {};
  bool wide = false;  // half angle past pi/2
};
void prepare_hand(const KernelHand& h, PreparedHand& out);
void add_displacement_simd(const PreparedHand& h, float share, const DisplacementSpan& s);

// Name of the instruction set the simd kernel dispatches to on this CPU
// ("avx2+fma", "baseline"), for benchmark labels.
const char* simd_kernel_isa();

}  // namespace twister::math
