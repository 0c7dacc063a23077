// The fast kernel: single precision, polynomial sin/cos, written as plain loops over
// restrict-qualified columns so the compiler vectorises them. On x86-64 GCC builds
// an AVX2+FMA clone and a baseline (SSE2) clone and picks one at load time
// (target_clones, an ifunc), so the shipped binary runs on any x86-64 CPU; other
// targets (aarch64: NEON) get the plain auto-vectorised loop.
#include <cstddef>

#include "twister/math/warp_kernels.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define TWISTER_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define TWISTER_SIMD_CLONES
#endif

#if defined(__GNUC__)
#define TWISTER_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define TWISTER_ALWAYS_INLINE inline
#endif

namespace twister::math {

namespace {

// sin and cos of x in [0, pi/2] (the half angle t*a/2 never leaves it): Taylor
// polynomials to x^11 and x^12, truncation error below 6e-8 on the whole range,
// i.e. at float rounding level, and no range reduction or table lookups.
TWISTER_ALWAYS_INLINE void sincos_half(float x, float& s, float& c) {
  const float x2 = x * x;
  s = x * (1.0f + x2 * (-1.6666667e-1f + x2 * (8.3333333e-3f + x2 * (-1.9841270e-4f +
                                 x2 * (2.7557319e-6f + x2 * -2.5052108e-8f)))));
  c = 1.0f + x2 * (-0.5f + x2 * (4.1666667e-2f + x2 * (-1.3888889e-3f + x2 * (2.4801587e-5f +
                                 x2 * (-2.7557319e-7f + x2 * 2.0876757e-9f)))));
}

struct HandF {
  float dx, dy, dz, mx, my, mz, xx, xy, xz, ex, ey, ez, tx, ty, tz, half, k;
};

HandF load(const KernelHand& h) {
  return {h.axis[0],  h.axis[1],  h.axis[2],  h.mid[0],          h.mid[1],          h.mid[2],
          h.chord[0], h.chord[1], h.chord[2], h.axis_x_chord[0], h.axis_x_chord[1],
          h.axis_x_chord[2],      h.shift[0], h.shift[1],        h.shift[2],        h.half_angle,
          h.cot_half};
}

TWISTER_ALWAYS_INLINE void accumulate(const HandF& h, float px, float py, float pz, float t,
                                      float& ox, float& oy, float& oz) {
  const float vx = px - h.mx;
  const float vy = py - h.my;
  const float vz = pz - h.mz;
  float sh;
  float ch;
  sincos_half(t * h.half, sh, ch);
  const float a = sh * ch;
  const float b = sh * sh;
  const float dv = h.dx * vx + h.dy * vy + h.dz * vz;
  const float cx = h.dy * vz - h.dz * vy;
  const float cy = h.dz * vx - h.dx * vz;
  const float cz = h.dx * vy - h.dy * vx;
  ox += a * (2.0f * cx + h.k * h.xx) + b * (2.0f * (h.dx * dv - vx) + h.k * h.ex) + t * h.tx;
  oy += a * (2.0f * cy + h.k * h.xy) + b * (2.0f * (h.dy * dv - vy) + h.k * h.ey) + t * h.ty;
  oz += a * (2.0f * cz + h.k * h.xz) + b * (2.0f * (h.dz * dv - vz) + h.k * h.ez) + t * h.tz;
}

TWISTER_SIMD_CLONES
void one_hand_loop(HandF h, const float* __restrict x, const float* __restrict y,
                   const float* __restrict z, const float* __restrict w, float* __restrict ox,
                   float* __restrict oy, float* __restrict oz, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    float rx = x[i];
    float ry = y[i];
    float rz = z[i];
    accumulate(h, x[i], y[i], z[i], w[i], rx, ry, rz);
    ox[i] = rx;
    oy[i] = ry;
    oz[i] = rz;
  }
}

TWISTER_SIMD_CLONES
void two_hand_loop(HandF h1, HandF h2, const float* __restrict x, const float* __restrict y,
                   const float* __restrict z, const float* __restrict w1,
                   const float* __restrict w2, float* __restrict ox, float* __restrict oy,
                   float* __restrict oz, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    // Sum the two displacements before adding them to P, as the spec's formula does.
    float dx = 0.0f;
    float dy = 0.0f;
    float dz = 0.0f;
    accumulate(h1, x[i], y[i], z[i], w1[i], dx, dy, dz);
    accumulate(h2, x[i], y[i], z[i], w2[i], dx, dy, dz);
    ox[i] = x[i] + dx;
    oy[i] = y[i] + dy;
    oz[i] = z[i] + dz;
  }
}

}  // namespace

void warp_one_simd(const KernelHand& h1, const KernelSpan& s) {
  one_hand_loop(load(h1), s.x, s.y, s.z, s.w1, s.out_x, s.out_y, s.out_z, s.n);
}

void warp_two_simd(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s) {
  two_hand_loop(load(h1), load(h2), s.x, s.y, s.z, s.w1, s.w2, s.out_x, s.out_y, s.out_z, s.n);
}

const char* simd_kernel_isa() {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "avx2+fma";
  return "baseline";
#else
  return "baseline";
#endif
}

}  // namespace twister::math
