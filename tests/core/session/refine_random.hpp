// Random strokes for the refinement properties (issue 13): one or two hands, turns
// about any axis up to 170 degrees, drags, clutch steps of hand 1, releases together
// or one after the other, drawn with rapidcheck inside a property. Test-only.
#pragma once

#include <rapidcheck.h>

#include <array>
#include <cmath>
#include <numbers>

#include "refine_harness.hpp"

namespace twister::session::test_support {

// U, V of the identity frame turned by `angle` about the unit `axis` (Rodrigues).
inline math::Frame turned(glm::dvec3 origin, glm::dvec3 axis, double angle) {
  const auto rot = [&](glm::dvec3 p) {
    return p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
           axis * glm::dot(axis, p) * (1.0 - std::cos(angle));
  };
  return math::frame_from_uv(origin, rot({1, 0, 0}), rot({0, 1, 0}));
}

inline glm::dvec3 any_point() {
  return {*rc::gen::inRange(-60, 61) / 100.0, *rc::gen::inRange(-60, 61) / 100.0,
          *rc::gen::inRange(-60, 61) / 100.0};
}

inline glm::dvec3 any_axis() {
  glm::dvec3 a(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101),
               *rc::gen::inRange(1, 101));
  return glm::normalize(a);
}

// One stroke of `mask` (1, 2 or 3): grab, move in a few steps, maybe a clutch step
// of hand 1, release (together or one after the other).
inline void random_stroke(RefineStation& s) {
  const auto mask = static_cast<std::uint8_t>(*rc::gen::inRange(1, 4));
  std::array<glm::dvec3, 2> from{any_point(), any_point()};
  if (glm::length(from[0] - from[1]) < 0.1) from[1] = -from[0] + glm::dvec3(0.2, 0, 0);
  std::array<glm::dvec3, 2> to{from[0] + 0.3 * any_point(), from[1] + 0.3 * any_point()};
  std::array<glm::dvec3, 2> axis{any_axis(), any_axis()};
  const std::array<double, 2> angle{*rc::gen::inRange(-170, 171) * std::numbers::pi / 180.0,
                                    *rc::gen::inRange(-170, 171) * std::numbers::pi / 180.0};
  const std::array<std::uint8_t, 2> grab{kGrab0, kGrab1};
  for (std::uint8_t h = 0; h < 2; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    s.hand(h, math::identity_frame(from[h]));
    s.button(grab[h], true);
  }
  (void)s.tick();
  const bool clutch = (mask & 2u) != 0 && *rc::gen::inRange(0, 4) == 0;
  for (int k = 1; k <= 4; ++k) {
    for (std::uint8_t h = 0; h < 2; ++h) {
      if ((mask & (1u << h)) == 0) continue;
      const double t = k / 4.0;
      s.hand(h, turned(from[h] + t * (to[h] - from[h]), axis[h], t * angle[h]));
    }
    if (clutch && k == 2) s.button(kFreeze1, true);
    if (clutch && k == 3) s.button(kFreeze1, false);
    (void)s.tick();
  }
  const bool together = *rc::gen::inRange(0, 2) == 0;
  for (std::uint8_t h = 0; h < 2; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    s.button(grab[h], false);
    if (!together) (void)s.tick();
  }
  (void)s.tick();
}

}  // namespace twister::session::test_support
