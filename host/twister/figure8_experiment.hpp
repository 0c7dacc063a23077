// The Figure 8 experiment (docs/math.md §9): a straight polyline bent by two hands
// through -180..135 degrees with each warp method; counts self-intersections and the
// sharpest turn. Host code; the warp itself is the station's WarpPlan.
#pragma once

#include <cstddef>
#include <glm/vec2.hpp>
#include <vector>

#include "twister/base/status.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::cli {

struct Figure8Setup {
  std::size_t points = 2001;  // polyline from x = -1 to x = 1
  double radius = 0.5;        // grabs at x = -0.5 and x = +0.5
  double lift = 0.6;          // both hands translate by (0, lift, 0)
};

struct Figure8Curve {
  int angle_deg = 0;  // hand 1 turns +angle about z, hand 2 -angle
  math::WarpMethod method = math::WarpMethod::twister;
  std::vector<glm::dvec2> points;  // the warped polyline (it stays in z = 0)
  std::size_t intersections = 0;   // pairs of non-adjacent segments that properly cross
  double sharpest_turn_deg = 0.0;  // largest angle between consecutive segments
};

// The angles of the figure: -180, -135, ..., 135.
std::vector<int> figure8_angles();

// Warps the polyline for one angle and method. At +-180 degrees the stroke passes
// through 179 degrees first, so the sign of the angle picks the sense (§2, §9).
Status run_figure8_curve(const Figure8Setup& setup, int angle_deg, math::WarpMethod method,
                         Figure8Curve& out);

// Pairs of non-adjacent segments of the polyline that cross properly.
std::size_t count_self_intersections(const std::vector<glm::dvec2>& line);

// Largest turning angle between consecutive segments, in degrees (180 = a cusp).
double sharpest_turn_deg(const std::vector<glm::dvec2>& line);

}  // namespace twister::cli
