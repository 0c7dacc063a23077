#include "figure8_experiment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <numbers>

#include "twister/math/warp_plan.hpp"

namespace twister::cli {

namespace {

math::Frame turned(const math::Frame& f, double angle_deg, glm::dvec3 move) {
  const glm::dquat q = glm::angleAxis(angle_deg * std::numbers::pi / 180.0, glm::dvec3(0, 0, 1));
  return math::Frame{f.origin + move, q * f.u, q * f.v, q * f.w};
}

double orient(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool properly_cross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d);
  const double o3 = orient(c, d, a), o4 = orient(c, d, b);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

}  // namespace

std::vector<int> figure8_angles() { return {-180, -135, -90, -45, 0, 45, 90, 135}; }

Status run_figure8_curve(const Figure8Setup& setup, int angle_deg, math::WarpMethod method,
                         Figure8Curve& out) {
  const std::size_t n = setup.points;
  std::vector<float> x(n), y(n, 0.0f), z(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = static_cast<float>(-1.0 + 2.0 * static_cast<double>(i) / static_cast<double>(n - 1));
  }
  std::vector<float> ox = x, oy = y, oz = z;
  std::vector<std::uint32_t> indices(n);
  std::vector<float> w1(n), w2(n);
  math::WarpPlan plan(math::WarpPlanStorage{indices, w1, w2});
  const std::array<math::Frame, 2> start{math::identity_frame({-0.5, 0.0, 0.0}),
                                         math::identity_frame({0.5, 0.0, 0.0})};
  const math::ConstVertexColumns rest(x, y, z);
  TWISTER_TRY(plan.build(rest, start, setup.radius, method));
  const glm::dvec3 lift(0.0, setup.lift, 0.0);
  if (std::abs(angle_deg) == 180) {
    // A stroke reaching a half turn keeps the sense it had on the way there.
    const double before = angle_deg > 0 ? 179.0 : -179.0;
    const std::array<math::Frame, 2> near{turned(start[0], before, lift),
                                          turned(start[1], -before, lift)};
    TWISTER_TRY(plan.update(near));
  }
  const std::array<math::Frame, 2> end{turned(start[0], angle_deg, lift),
                                       turned(start[1], -angle_deg, lift)};
  TWISTER_TRY(plan.update(end));
  TWISTER_TRY(plan.apply(rest, math::VertexColumns{ox, oy, oz}));
  out.angle_deg = angle_deg;
  out.method = method;
  out.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.points[i] = glm::dvec2(ox[i], oy[i]);
  out.intersections = count_self_intersections(out.points);
  out.sharpest_turn_deg = sharpest_turn_deg(out.points);
  return ok_status();
}

std::size_t count_self_intersections(const std::vector<glm::dvec2>& line) {
  const std::size_t segs = line.size() < 2 ? 0 : line.size() - 1;
  // Bounding boxes first: most segment pairs are far apart.
  std::size_t count = 0;
  for (std::size_t i = 0; i < segs; ++i) {
    const glm::dvec2 a = line[i], b = line[i + 1];
    const glm::dvec2 lo = glm::min(a, b), hi = glm::max(a, b);
    for (std::size_t j = i + 2; j < segs; ++j) {
      const glm::dvec2 c = line[j], d = line[j + 1];
      if (std::max(c.x, d.x) < lo.x || std::min(c.x, d.x) > hi.x || std::max(c.y, d.y) < lo.y ||
          std::min(c.y, d.y) > hi.y) {
        continue;
      }
      if (properly_cross(a, b, c, d)) ++count;
    }
  }
  return count;
}

double sharpest_turn_deg(const std::vector<glm::dvec2>& line) {
  double worst = 0.0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const glm::dvec2 u = line[i] - line[i - 1], v = line[i + 1] - line[i];
    const double lu = glm::length(u), lv = glm::length(v);
    if (lu == 0.0 || lv == 0.0) continue;
    const double c = std::clamp(glm::dot(u, v) / (lu * lv), -1.0, 1.0);
    worst = std::max(worst, std::acos(c) * 180.0 / std::numbers::pi);
  }
  return worst;
}

}  // namespace twister::cli
