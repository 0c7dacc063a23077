// Per-vertex warp kernels over dense float columns: the per-update hot path.
// Both kernels compute, per hand with decay weight t,
//   disp = sh*ch*(2 D x v + k X) + sh^2*(2 (D(D.v) - v) + k (D x X)) + t T,
//   v = P - M, sh = sin(t*a/2), ch = cos(t*a/2), k = cot(a/2),
// which is S(t)(P) - P for twister (T = dD) and rottran (M = O, k = 0, T = OO').
// `scalar` is the reference (double arithmetic, std::sin/cos, one vertex at a
// time); `simd` is single precision with polynomial sin/cos, auto-vectorised and
// dispatched at run time (AVX2+FMA where the CPU has them, baseline otherwise).
#pragma once

#include <cstddef>
#include <cstdint>

namespace twister::math {

enum class KernelKind : std::uint8_t { scalar, simd };

// One hand's per-update parameters in kernel form (see above), world frame.
struct KernelHand {
  float axis[3] = {0.0f, 0.0f, 1.0f};          // D
  float mid[3] = {0.0f, 0.0f, 0.0f};           // M (O for rottran)
  float chord[3] = {0.0f, 0.0f, 0.0f};         // X (0 for rottran)
  float axis_x_chord[3] = {0.0f, 0.0f, 0.0f};  // D x X
  float shift[3] = {0.0f, 0.0f, 0.0f};         // T: dD (twister), OO' (rottran, pure)
  float half_angle = 0.0f;                     // a/2 in [0, pi/2]
  float cot_half = 0.0f;                       // k
  // Double copies for the scalar reference kernel.
  double axis_d[3] = {0.0, 0.0, 1.0};
  double mid_d[3] = {0.0, 0.0, 0.0};
  double chord_d[3] = {0.0, 0.0, 0.0};
  double axis_x_chord_d[3] = {0.0, 0.0, 0.0};
  double shift_d[3] = {0.0, 0.0, 0.0};
  double half_angle_d = 0.0;
  double cot_half_d = 0.0;
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
void warp_two_simd(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s);

// Name of the instruction set the simd kernel dispatches to on this CPU
// ("avx2+fma", "baseline"), for benchmark labels.
const char* simd_kernel_isa();

}  // namespace twister::math
