// PointWarp: a space warp evaluated one point at a time in double precision, for
// work that needs the warp between vertices (adaptive refinement evaluates it at
// edge midpoints). Positions are rest positions in the mesh's frame (metres); the
// result is where the warp takes that point. Implementations must be deterministic
// (the same point gives the same bits) and must not allocate.
#pragma once

#include <cstddef>
#include <glm/vec3.hpp>
#include <limits>

namespace twister::mesh {

class PointWarp {
 public:
  virtual ~PointWarp() = default;

  glm::dvec3 warp(glm::dvec3 rest_m) const { return do_warp(rest_m); }

  // Optional: the warp of n <= kFloatBatch points in single precision (a filter: the
  // refiner settles with it only the edges it can prove within the threshold). False:
  // not offered (nothing written).
  static constexpr std::size_t kFloatBatch = 256;
  bool warp_float(const float* x, const float* y, const float* z, float* out_x, float* out_y,
                  float* out_z, std::size_t n) const {
    return do_warp_float(x, y, z, out_x, out_y, out_z, n);
  }
  // A bound on |warp_float(q) - warp(p)| (metres) for every point p whose coordinates
  // are at most extent_m in magnitude and any q within 2^-24 |p| of it per coordinate
  // (a midpoint rounded to float). Must be rigorous: the refiner's verdicts rely on it.
  double float_error_m(double extent_m) const { return do_float_error_m(extent_m); }

 private:
  virtual glm::dvec3 do_warp(glm::dvec3 rest_m) const = 0;
  virtual bool do_warp_float(const float*, const float*, const float*, float*, float*, float*,
                             std::size_t) const {
    return false;
  }
  virtual double do_float_error_m(double) const { return std::numeric_limits<double>::infinity(); }
};

}  // namespace twister::mesh
