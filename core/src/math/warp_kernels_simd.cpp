// The fast kernel: single precision, polynomial sin/cos, written as plain loops over
// restrict-qualified columns so the compiler vectorises them. On x86-64 GCC builds
// an AVX2+FMA clone and a baseline (SSE2) clone and picks one at load time
// (target_clones, an ifunc), so the shipped binary runs on any x86-64 CPU; other
// targets (aarch64: NEON) get the plain auto-vectorised loop.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

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

// sin and cos of x in [0, pi/2] (the half angle t*a/2 of a minimal screw), without
// range reduction or tables: sin = x + x^3 p(x^2) (degree 9) and cos = 1 + x^2 q(x^2)
// (degree 10), least-squares fits on Chebyshev nodes (near-minimax), float
// coefficients. Largest error on [0, pi/2]: 4e-8 (sin), 6e-9 (cos), i.e. float
// rounding level; one FMA fewer each than Taylor polynomials of that accuracy.
TWISTER_ALWAYS_INLINE void sincos_half(float x, float& s, float& c) {
  const float x2 = x * x;
  float p = 2.63481525e-06f;
  p = p * x2 - 1.98227615e-04f;
  p = p * x2 + 8.3332425e-03f;
  p = p * x2 - 1.66666657e-01f;
  s = x + (x * x2) * p;
  float q = -2.62979313e-07f;
  q = q * x2 + 2.47745993e-05f;
  q = q * x2 - 1.38886517e-03f;
  q = q * x2 + 4.16666605e-02f;
  q = q * x2 - 0.5f;
  c = 1.0f + x2 * q;
}

// cos alone (the decay weights).
TWISTER_ALWAYS_INLINE float cos_quarter(float x) {
  const float x2 = x * x;
  float q = -2.62979313e-07f;
  q = q * x2 + 2.47745993e-05f;
  q = q * x2 - 1.38886517e-03f;
  q = q * x2 + 4.16666605e-02f;
  q = q * x2 - 0.5f;
  return 1.0f + x2 * q;
}

// The same for x in [0, pi) (a screw the long way round, angle up to 2 pi,
// docs/unwrap.md): sin(x) = sin(pi - x), cos(x) = -cos(pi - x) above pi/2, as two
// selects the compiler turns into blends. Only called when a hand's half angle
// exceeds pi/2, so minimal strokes keep the cheaper loop.
TWISTER_ALWAYS_INLINE void sincos_half_wide(float x, float& s, float& c) {
  constexpr float kHalfPi = 1.57079632679489662f;
  constexpr float kPi = 3.14159265358979324f;
  const bool over = x > kHalfPi;
  sincos_half(over ? kPi - x : x, s, c);
  c = over ? -c : c;
}

// Per-hand constants of the rearranged displacement (v = P - M expanded so that the
// loop needs 13 constants and about 41 flops per hand instead of 16 and 50):
//   disp = A2 (D x P + F) + B2 (D (D.P) - P + G) + t T,
//   A2 = 2 sh ch, B2 = 2 sh^2, F = kX/2 - D x M, G = k(D x X)/2 - D(D.M) + M.
// F and G are formed in double; for tiny angles they grow like 1/a while A2 and B2
// shrink like a, so their float rounding stays at the scale of the displacement.
struct HandF {
  float dx, dy, dz, fx, fy, fz, gx, gy, gz, tx, ty, tz, half;
};

HandF load(const KernelHand& h) {
  const double* d = h.axis;
  const double* m = h.mid;
  const double k2 = 0.5 * h.cot_half;
  const double dm = d[0] * m[0] + d[1] * m[1] + d[2] * m[2];
  const double cx = d[1] * m[2] - d[2] * m[1];
  const double cy = d[2] * m[0] - d[0] * m[2];
  const double cz = d[0] * m[1] - d[1] * m[0];
  const auto f = [](double v) { return static_cast<float>(v); };
  return {f(d[0]),
          f(d[1]),
          f(d[2]),
          f(k2 * h.chord[0] - cx),
          f(k2 * h.chord[1] - cy),
          f(k2 * h.chord[2] - cz),
          f(k2 * h.axis_x_chord[0] - d[0] * dm + m[0]),
          f(k2 * h.axis_x_chord[1] - d[1] * dm + m[1]),
          f(k2 * h.axis_x_chord[2] - d[2] * dm + m[2]),
          f(h.shift[0]),
          f(h.shift[1]),
          f(h.shift[2]),
          f(h.half_angle)};
}

// acc += displacement of P for one hand with weight t (kWide: half angle up to pi).
template <bool kWide>
TWISTER_ALWAYS_INLINE void accumulate(const HandF& h, float px, float py, float pz, float t,
                                      float& ox, float& oy, float& oz) {
  float sh;
  float ch;
  if constexpr (kWide) {
    sincos_half_wide(t * h.half, sh, ch);
  } else {
    sincos_half(t * h.half, sh, ch);
  }
  const float sh2 = sh + sh;
  const float a2 = sh2 * ch;
  const float b2 = sh2 * sh;
  // One operation per statement, in an order where each one is an FMA: without
  // -ffast-math the compiler may contract a*b + c but may not reassociate sums.
  float dp = h.dx * px;
  dp += h.dy * py;
  dp += h.dz * pz;
  float ux = h.fx + h.dy * pz;
  ux -= h.dz * py;
  float uy = h.fy + h.dz * px;
  uy -= h.dx * pz;
  float uz = h.fz + h.dx * py;
  uz -= h.dy * px;
  float wx = h.gx - px;
  wx += h.dx * dp;
  float wy = h.gy - py;
  wy += h.dy * dp;
  float wz = h.gz - pz;
  wz += h.dz * dp;
  ox += a2 * ux;
  ox += b2 * wx;
  ox += t * h.tx;
  oy += a2 * uy;
  oy += b2 * wy;
  oy += t * h.ty;
  oz += a2 * uz;
  oz += b2 * wz;
  oz += t * h.tz;
}

template <bool kWide>
TWISTER_ALWAYS_INLINE void one_hand_body(const HandF& h, const float* __restrict x,
                                         const float* __restrict y, const float* __restrict z,
                                         const float* __restrict w, float* __restrict ox,
                                         float* __restrict oy, float* __restrict oz,
                                         std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    float rx = x[i];
    float ry = y[i];
    float rz = z[i];
    accumulate<kWide>(h, x[i], y[i], z[i], w[i], rx, ry, rz);
    ox[i] = rx;
    oy[i] = ry;
    oz[i] = rz;
  }
}

template <bool kWide>
TWISTER_ALWAYS_INLINE void two_hand_body(const HandF& h1, const HandF& h2,
                                         const float* __restrict x, const float* __restrict y,
                                         const float* __restrict z, const float* __restrict w1,
                                         const float* __restrict w2, float* __restrict ox,
                                         float* __restrict oy, float* __restrict oz,
                                         std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    // Accumulating onto P directly (no zero-initialised sum: without -ffast-math the
    // compiler must keep 0 + x, which costs three adds per vertex).
    float rx = x[i];
    float ry = y[i];
    float rz = z[i];
    accumulate<kWide>(h1, x[i], y[i], z[i], w1[i], rx, ry, rz);
    accumulate<kWide>(h2, x[i], y[i], z[i], w2[i], rx, ry, rz);
    ox[i] = rx;
    oy[i] = ry;
    oz[i] = rz;
  }
}

TWISTER_SIMD_CLONES
void one_hand_loop(HandF h, const float* __restrict x, const float* __restrict y,
                   const float* __restrict z, const float* __restrict w, float* __restrict ox,
                   float* __restrict oy, float* __restrict oz, std::size_t n) {
  one_hand_body<false>(h, x, y, z, w, ox, oy, oz, n);
}

TWISTER_SIMD_CLONES
void one_hand_loop_wide(HandF h, const float* __restrict x, const float* __restrict y,
                        const float* __restrict z, const float* __restrict w, float* __restrict ox,
                        float* __restrict oy, float* __restrict oz, std::size_t n) {
  one_hand_body<true>(h, x, y, z, w, ox, oy, oz, n);
}

TWISTER_SIMD_CLONES
void two_hand_loop(HandF h1, HandF h2, const float* __restrict x, const float* __restrict y,
                   const float* __restrict z, const float* __restrict w1,
                   const float* __restrict w2, float* __restrict ox, float* __restrict oy,
                   float* __restrict oz, std::size_t n) {
  two_hand_body<false>(h1, h2, x, y, z, w1, w2, ox, oy, oz, n);
}

TWISTER_SIMD_CLONES
void two_hand_loop_wide(HandF h1, HandF h2, const float* __restrict x, const float* __restrict y,
                        const float* __restrict z, const float* __restrict w1,
                        const float* __restrict w2, float* __restrict ox, float* __restrict oy,
                        float* __restrict oz, std::size_t n) {
  two_hand_body<true>(h1, h2, x, y, z, w1, w2, ox, oy, oz, n);
}

// A screw the long way round has a half angle past pi/2 (weights reach 1).
bool wide(const KernelHand& h) { return h.half_angle > 0.5 * 3.14159265358979323846; }

}  // namespace

void warp_one_simd(const KernelHand& h1, const KernelSpan& s) {
  if (wide(h1)) {
    one_hand_loop_wide(load(h1), s.x, s.y, s.z, s.w1, s.out_x, s.out_y, s.out_z, s.n);
  } else {
    one_hand_loop(load(h1), s.x, s.y, s.z, s.w1, s.out_x, s.out_y, s.out_z, s.n);
  }
}

void warp_two_simd(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s) {
  if (wide(h1) || wide(h2)) {
    two_hand_loop_wide(load(h1), load(h2), s.x, s.y, s.z, s.w1, s.w2, s.out_x, s.out_y, s.out_z,
                       s.n);
  } else {
    two_hand_loop(load(h1), load(h2), s.x, s.y, s.z, s.w1, s.w2, s.out_x, s.out_y, s.out_z, s.n);
  }
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

// Plain loop over restrict columns; sqrt vectorises (this file is built with
// -fno-math-errno: its argument is never negative).
TWISTER_SIMD_CLONES
void decay_weights_simd(const DecaySpan& s, const float grab[3], const float unit[3], float stretch,
                        float radius) {
  const float* __restrict x = s.x;
  const float* __restrict y = s.y;
  const float* __restrict z = s.z;
  float* __restrict w = s.w;
  const float gx = grab[0], gy = grab[1], gz = grab[2];
  const float ux = unit[0], uy = unit[1], uz = unit[2];
  constexpr float kHalfPiF = 1.57079632679489662f;
  const float scale = kHalfPiF / radius;
  const float c0 = cos_quarter(kHalfPiF);
  for (std::size_t i = 0; i < s.n; ++i) {
    float px = x[i] - gx;
    float py = y[i] - gy;
    float pz = z[i] - gz;
    // Branch-free (a select or compare kept this loop scalar): max(proj, 0) and
    // min(x, pi/2) from fabs; the polynomial's value at pi/2 (c0, ~1e-8) subtracted so
    // that the weight outside the radius is exactly 0 (a tiny one would make the warp
    // kernel compute with denormals).
    const float proj = px * ux + py * uy + pz * uz;
    const float k = 0.5f * (proj + std::fabs(proj)) * stretch;
    px += k * ux;
    py += k * uy;
    pz += k * uz;
    const float arg = std::sqrt(px * px + py * py + pz * pz) * scale;
    const float c = cos_quarter(0.5f * (arg + kHalfPiF - std::fabs(arg - kHalfPiF))) - c0;
    w[i] = c * c;
  }
}

// The symmetric float path (docs/math.md §11.7): one grab point's weights with its
// several squashes. Three plain loops over small stack columns (the squash loop runs
// per neighbour over all points, so the inner loop is the one over points).
TWISTER_SIMD_CLONES
void image_weights_simd(const DecaySpan& s, const float grab_hi[3], const float grab_lo[3],
                        const float* squash, std::size_t count, float radius) {
  const std::size_t n = std::min(s.n, kImageChunk);
  float vx[kImageChunk];
  float vy[kImageChunk];
  float vz[kImageChunk];
  float d2[kImageChunk];
  float most[kImageChunk];
  {
    const float* __restrict x = s.x;
    const float* __restrict y = s.y;
    const float* __restrict z = s.z;
    const float hx = grab_hi[0], hy = grab_hi[1], hz = grab_hi[2];
    const float lx = grab_lo[0], ly = grab_lo[1], lz = grab_lo[2];
    for (std::size_t i = 0; i < n; ++i) {
      const float px = (x[i] - hx) - lx;
      const float py = (y[i] - hy) - ly;
      const float pz = (z[i] - hz) - lz;
      vx[i] = px;
      vy[i] = py;
      vz[i] = pz;
      float d = px * px;
      d += py * py;
      d += pz * pz;
      d2[i] = d;
      most[i] = d;
    }
  }
  for (std::size_t j = 0; j < count; ++j) {
    const float ux = squash[4 * j], uy = squash[4 * j + 1], uz = squash[4 * j + 2];
    const float stretch = squash[4 * j + 3];
    for (std::size_t i = 0; i < n; ++i) {
      float proj = vx[i] * ux;
      proj += vy[i] * uy;
      proj += vz[i] * uz;
      // |v + k u|^2 = d^2 + k (2 proj + k), k = max(proj, 0) stretch; the largest
      // (the smallest weight) by max(a, b) = (a + b + |a - b|) / 2, branch-free.
      const float k = 0.5f * (proj + std::fabs(proj)) * stretch;
      const float sq = d2[i] + k * (proj + proj + k);
      most[i] = 0.5f * (most[i] + sq + std::fabs(most[i] - sq));
    }
  }
  constexpr float kHalfPiF = 1.57079632679489662f;
  const float scale = kHalfPiF / radius;
  float* __restrict w = s.w;
  // The weight cos^2 inside the ball, exactly 0 outside, and 0 below 2^-32 too: a
  // weight that small moves a point by < 2^-32 of the hand's motion, and in the warp
  // kernel the cube of its sine would underflow (denormal assists cost more than the
  // kernel). A plain select keeps this loop scalar, so 8 lanes are written with vector
  // extensions (GCC and Clang), the comparisons as bit masks.
  constexpr float kTiny = 0x1p-32f;
  for (std::size_t i = 0; i < n; ++i) most[i] = std::sqrt(most[i]) * scale;
  using V = float __attribute__((vector_size(32)));
  using M = std::int32_t __attribute__((vector_size(32)));
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    V arg;
    std::memcpy(&arg, most + i, sizeof arg);
    // cos_quarter's polynomial (no vector function: a 32-byte vector argument would
    // change the baseline clone's ABI).
    const V x2 = arg * arg;
    V q = x2 * -2.62979313e-07f + 2.47745993e-05f;
    q = q * x2 - 1.38886517e-03f;
    q = q * x2 + 4.16666605e-02f;
    q = q * x2 - 0.5f;
    const V c = 1.0f + x2 * q;
    const V wv = c * c;
    const M keep = (arg < kHalfPiF) & (wv > kTiny);
    M bits;
    std::memcpy(&bits, &wv, sizeof bits);
    bits &= keep;
    std::memcpy(w + i, &bits, sizeof bits);
  }
  for (; i < n; ++i) {
    const float c = cos_quarter(most[i]);
    w[i] = most[i] < kHalfPiF && c * c > kTiny ? c * c : 0.0f;
  }
}

namespace {

template <bool kWide>
TWISTER_ALWAYS_INLINE void displacement_body(const HandF& h, float share, const float* __restrict x,
                                             const float* __restrict y, const float* __restrict z,
                                             const float* __restrict w, float* __restrict dx,
                                             float* __restrict dy, float* __restrict dz,
                                             std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    float rx = 0.0f;
    float ry = 0.0f;
    float rz = 0.0f;
    accumulate<kWide>(h, x[i], y[i], z[i], w[i], rx, ry, rz);
    dx[i] += share * rx;
    dy[i] += share * ry;
    dz[i] += share * rz;
  }
}

TWISTER_SIMD_CLONES
void displacement_loop(HandF h, float share, const float* __restrict x, const float* __restrict y,
                       const float* __restrict z, const float* __restrict w, float* __restrict dx,
                       float* __restrict dy, float* __restrict dz, std::size_t n) {
  displacement_body<false>(h, share, x, y, z, w, dx, dy, dz, n);
}

TWISTER_SIMD_CLONES
void displacement_loop_wide(HandF h, float share, const float* __restrict x,
                            const float* __restrict y, const float* __restrict z,
                            const float* __restrict w, float* __restrict dx, float* __restrict dy,
                            float* __restrict dz, std::size_t n) {
  displacement_body<true>(h, share, x, y, z, w, dx, dy, dz, n);
}

}  // namespace

void prepare_hand(const KernelHand& h, PreparedHand& out) {
  const HandF f = load(h);
  static_assert(sizeof f == sizeof out.c);
  std::memcpy(out.c, &f, sizeof f);
  out.wide = wide(h);
}

void add_displacement_simd(const PreparedHand& h, float share, const DisplacementSpan& s) {
  HandF f;
  std::memcpy(&f, h.c, sizeof f);
  if (h.wide) {
    displacement_loop_wide(f, share, s.x, s.y, s.z, s.w, s.dx, s.dy, s.dz, s.n);
  } else {
    displacement_loop(f, share, s.x, s.y, s.z, s.w, s.dx, s.dy, s.dz, s.n);
  }
}

}  // namespace twister::math
