// The reference kernel: one vertex at a time in double with std::sin/std::cos.
#include <cmath>

#include "twister/math/warp_kernels.hpp"

namespace twister::math {

namespace {
struct Disp {
  double x, y, z;
};

Disp hand_displacement(const KernelHand& h, double px, double py, double pz, double t) {
  const double* d = h.axis;
  const double vx = px - h.mid[0];
  const double vy = py - h.mid[1];
  const double vz = pz - h.mid[2];
  const double half = t * h.half_angle;
  const double sh = std::sin(half);
  const double ch = std::cos(half);
  const double a = sh * ch;
  const double b = sh * sh;
  const double k = h.cot_half;
  const double dv = d[0] * vx + d[1] * vy + d[2] * vz;
  const double cx = d[1] * vz - d[2] * vy;
  const double cy = d[2] * vx - d[0] * vz;
  const double cz = d[0] * vy - d[1] * vx;
  return {a * (2.0 * cx + k * h.chord[0]) + b * (2.0 * (d[0] * dv - vx) + k * h.axis_x_chord[0]) +
              t * h.shift[0],
          a * (2.0 * cy + k * h.chord[1]) + b * (2.0 * (d[1] * dv - vy) + k * h.axis_x_chord[1]) +
              t * h.shift[1],
          a * (2.0 * cz + k * h.chord[2]) + b * (2.0 * (d[2] * dv - vz) + k * h.axis_x_chord[2]) +
              t * h.shift[2]};
}
}  // namespace

void warp_one_scalar(const KernelHand& h1, const KernelSpan& s) {
  for (std::size_t i = 0; i < s.n; ++i) {
    const double px = s.x[i];
    const double py = s.y[i];
    const double pz = s.z[i];
    const Disp d1 = hand_displacement(h1, px, py, pz, s.w1[i]);
    s.out_x[i] = static_cast<float>(px + d1.x);
    s.out_y[i] = static_cast<float>(py + d1.y);
    s.out_z[i] = static_cast<float>(pz + d1.z);
  }
}

void warp_two_scalar(const KernelHand& h1, const KernelHand& h2, const KernelSpan& s) {
  for (std::size_t i = 0; i < s.n; ++i) {
    const double px = s.x[i];
    const double py = s.y[i];
    const double pz = s.z[i];
    const Disp d1 = hand_displacement(h1, px, py, pz, s.w1[i]);
    const Disp d2 = hand_displacement(h2, px, py, pz, s.w2[i]);
    s.out_x[i] = static_cast<float>(px + d1.x + d2.x);
    s.out_y[i] = static_cast<float>(py + d1.y + d2.y);
    s.out_z[i] = static_cast<float>(pz + d1.z + d2.z);
  }
}

}  // namespace twister::math
