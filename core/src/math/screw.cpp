#include "twister/math/screw.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <numbers>

namespace twister::math {

namespace {
glm::dvec3 rotate(glm::dvec3 axis, double angle, glm::dvec3 v) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}
}  // namespace

glm::dvec3 Screw::axis_point() const { return mid + glm::cross(axis, chord) * (0.5 * cot_half); }

glm::dquat relative_rotation(const Frame& start, const Frame& end) {
  // R from the frames rather than the axis sum of the paper: the sum has the wrong
  // sign or vanishes for some axes (docs/math.md §2).
  const glm::dmat3 from(start.u, start.v, start.w);
  const glm::dmat3 to(end.u, end.v, end.w);
  return glm::quat_cast(to * glm::transpose(from));
}

Screw long_way_round(const Screw& minimal) {
  if (minimal.pure_translation) return minimal;
  Screw s = minimal;
  s.axis = -minimal.axis;
  s.angle = 2.0 * std::numbers::pi - minimal.angle;
  s.slide = -minimal.slide;
  // cot((2 pi - a)/2) = cot(pi - a/2) = -cot(a/2), exactly; M, X and A stay.
  s.cot_half = -minimal.cot_half;
  return s;
}

Screw compute_screw(const Frame& start, const Frame& end, std::optional<glm::dvec3> previous_axis) {
  glm::dquat q = relative_rotation(start, end);
  if (q.w < 0.0) q = -q;  // a in [0, pi]
  const glm::dvec3 vec(q.x, q.y, q.z);
  const double sin_half = glm::length(vec);
  const double angle = 2.0 * std::atan2(sin_half, q.w);
  const glm::dvec3 shift = end.origin - start.origin;

  Screw s;
  if (!(angle > kPureTranslationAngle)) {
    s.pure_translation = true;
    if (previous_axis) s.axis = *previous_axis;
    s.mid = start.origin;
    s.chord = shift;
    return s;
  }
  s.pure_translation = false;
  s.angle = angle;
  s.axis = vec / sin_half;
  if (previous_axis && std::numbers::pi - angle < kHalfTurnTolerance &&
      glm::dot(s.axis, *previous_axis) < 0.0) {
    s.axis = -s.axis;  // both senses reach the end pose; keep the stroke's
  }
  s.slide = glm::dot(s.axis, shift);
  const glm::dvec3 projected = end.origin - s.slide * s.axis;  // O''
  s.mid = 0.5 * (start.origin + projected);
  s.chord = projected - start.origin;
  s.cot_half = std::cos(0.5 * angle) / std::sin(0.5 * angle);
  return s;
}

glm::dvec3 screw_at(const Screw& s, double t, glm::dvec3 p) {
  if (s.pure_translation) return p + t * s.chord;
  const double theta = t * s.angle;
  const double sh = std::sin(0.5 * theta);
  // c1 = sin^2(ta/2) cot(a/2) and c2 = sin(ta) cot(a/2) / 2 stay finite as a -> 0,
  // where the axis point A itself runs off to infinity.
  const double c1 = sh * sh * s.cot_half;
  const double c2 = 0.5 * std::sin(theta) * s.cot_half;
  return s.mid + rotate(s.axis, theta, p - s.mid) + c1 * glm::cross(s.axis, s.chord) +
         c2 * s.chord + (t * s.slide) * s.axis;
}

glm::dvec3 full_screw_image(const Screw& s, const Frame& start, const Frame& end, glm::dvec3 p) {
  if (s.pure_translation) return p + s.chord;
  const glm::dvec3 a = s.axis_point();
  const glm::dvec3 ap = p - a;
  return glm::dot(ap, start.u) * end.u + glm::dot(ap, start.v) * end.v +
         glm::dot(ap, start.w) * end.w + s.slide * s.axis + a;
}

glm::dvec3 rottran_at(const Screw& s, const Frame& start, const Frame& end, double t,
                      glm::dvec3 p) {
  const glm::dvec3 shift = end.origin - start.origin;
  if (s.pure_translation) return p + t * shift;
  return start.origin + rotate(s.axis, t * s.angle, p - start.origin) + t * shift;
}

}  // namespace twister::math
