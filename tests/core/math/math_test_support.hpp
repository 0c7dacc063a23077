// Shared generators and helpers for the math tests (rapidcheck).
#pragma once

#include <rapidcheck.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <numbers>
#include <vector>

#include "twister/math/frame.hpp"
#include "twister/math/vertex_columns.hpp"

namespace twister::math::test {

// A double in [lo, hi] with 1e-6 resolution.
inline rc::Gen<double> gen_real(double lo, double hi) {
  return rc::gen::map(rc::gen::inRange<int>(0, 1000001),
                      [lo, hi](int i) { return lo + (hi - lo) * (i / 1e6); });
}

inline rc::Gen<glm::dvec3> gen_point(double extent) {
  return rc::gen::apply([](double x, double y, double z) { return glm::dvec3(x, y, z); },
                        gen_real(-extent, extent), gen_real(-extent, extent),
                        gen_real(-extent, extent));
}

inline rc::Gen<glm::dvec3> gen_unit() {
  return rc::gen::map(rc::gen::suchThat(gen_point(1.0),
                                        [](glm::dvec3 v) {
                                          const double l = glm::length(v);
                                          return l > 0.1 && l <= 1.0;
                                        }),
                      [](glm::dvec3 v) { return glm::normalize(v); });
}

inline Frame frame_from_quat(glm::dvec3 origin, glm::dquat q) {
  const glm::dmat3 m = glm::mat3_cast(glm::normalize(q));
  return Frame{origin, m[0], m[1], m[2]};
}

inline Frame rotated(const Frame& f, glm::dvec3 axis, double angle, glm::dvec3 new_origin) {
  const glm::dquat q = glm::angleAxis(angle, axis);
  return Frame{new_origin, q * f.u, q * f.v, q * f.w};
}

inline rc::Gen<Frame> gen_frame(double extent) {
  return rc::gen::apply(
      [](glm::dvec3 o, glm::dvec3 axis, double angle) {
        return frame_from_quat(o, glm::angleAxis(angle, axis));
      },
      gen_point(extent), gen_unit(), gen_real(0.0, std::numbers::pi));
}

// An end frame for `start`: a rotation of a chosen kind (0 general, 1 near a half
// turn, 2 tiny, 3 none = pure translation) about a random axis, and a random move.
inline rc::Gen<Frame> gen_end_frame(const Frame& start, double extent) {
  return rc::gen::apply(
      [start](glm::dvec3 axis, int kind, double general, double tiny, glm::dvec3 move) {
        double angle = general;
        if (kind == 1) angle = std::numbers::pi - tiny;
        if (kind == 2) angle = tiny;
        if (kind == 3) angle = 0.0;
        return rotated(start, axis, angle, start.origin + move);
      },
      gen_unit(), rc::gen::inRange(0, 4), gen_real(0.0, std::numbers::pi), gen_real(0.0, 1e-6),
      gen_point(extent));
}

inline double distance(glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b); }

// n positions as owned columns, e.g. the output of a warp.
struct Columns {
  explicit Columns(std::size_t n, float fill = 0.0f) : x(n, fill), y(n, fill), z(n, fill) {}
  std::vector<float> x, y, z;
  VertexColumns cols() { return {x, y, z}; }
  glm::dvec3 at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

}  // namespace twister::math::test
