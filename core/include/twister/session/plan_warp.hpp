// PlanWarp: a math::WarpPlan as the refiner's mesh::PointWarp: double precision,
// weights from the rest position (chain step 0: exactly the function the plan's
// weights came from), and the plan's float batch with its error bound for the
// refiner's float filter. Holds a reference: the plan must outlive it.
#pragma once

#include <cstddef>

#include "twister/math/warp_plan.hpp"
#include "twister/mesh/point_warp.hpp"

namespace twister::session {

class PlanWarp final : public mesh::PointWarp {
 public:
  explicit PlanWarp(const math::WarpPlan& plan) : plan_(plan) {}

 private:
  glm::dvec3 do_warp(glm::dvec3 rest_m) const override { return plan_.warp_point(rest_m); }
  bool do_warp_float(const float* x, const float* y, const float* z, float* ox, float* oy,
                     float* oz, std::size_t n) const override {
    return plan_.warp_points_float(x, y, z, ox, oy, oz, n);
  }
  double do_float_error_m(double extent_m) const override {
    return plan_.float_error_bound(extent_m);
  }
  const math::WarpPlan& plan_;
};

}  // namespace twister::session
