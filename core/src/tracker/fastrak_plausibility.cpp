// Plausibility checks (docs/fastrak-protocol.md §3.8): non-finite values, position range (400 in /
// 1016 cm), angle range, direction-cosine frame, quaternion norm.
#include "fastrak_plausibility.hpp"

#include <cmath>

namespace twister::tracker::internal {
namespace {

bool all_finite(const float* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

bool dcm_ok(const std::array<float, 9>& m, double tol) {
  auto at = [&](int r, int c) {
    return static_cast<double>(m[static_cast<std::size_t>(r) * 3 + static_cast<std::size_t>(c)]);
  };
  for (int i = 0; i < 3; ++i) {
    double row = 0.0, col = 0.0;
    for (int k = 0; k < 3; ++k) {
      row += at(i, k) * at(i, k);
      col += at(k, i) * at(k, i);
    }
    if (std::fabs(std::sqrt(row) - 1.0) > tol || std::fabs(std::sqrt(col) - 1.0) > tol) {
      return false;
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += at(k, i) * at(k, j);
      if (std::fabs(d) > tol) return false;
    }
  }
  const double det = at(0, 0) * (at(1, 1) * at(2, 2) - at(1, 2) * at(2, 1)) -
                     at(0, 1) * (at(1, 0) * at(2, 2) - at(1, 2) * at(2, 0)) +
                     at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
  return det > 0.0;
}

}  // namespace

std::optional<PoseError> check_plausibility(const FastrakPose& pose, unsigned dcm_rows,
                                            const FastrakConfig& config) {
  const double tol = config.format == Format::ascii ? 0.01 : 0.001;
  const float pos_limit = config.units == Units::inches ? 400.0f : 1016.0f;
  if (!all_finite(pose.position.data(), 3) || !all_finite(pose.euler_deg.data(), 3) ||
      !all_finite(pose.dcm.data(), 9) || !all_finite(pose.quaternion.data(), 4)) {
    return PoseError::nonfinite;
  }
  for (float v : pose.position) {
    if (std::fabs(v) > pos_limit) return PoseError::position_range;
  }
  if (std::fabs(pose.euler_deg[0]) > 180.0f || std::fabs(pose.euler_deg[1]) > 90.0f ||
      std::fabs(pose.euler_deg[2]) > 180.0f) {
    return PoseError::angle_range;
  }
  if (dcm_rows != 0 && (dcm_rows != 7u || !dcm_ok(pose.dcm, tol))) return PoseError::bad_dcm;
  if (pose.has.quaternion) {
    double n2 = 0.0;
    for (float q : pose.quaternion) n2 += static_cast<double>(q) * static_cast<double>(q);
    if (std::fabs(std::sqrt(n2) - 1.0) > tol) return PoseError::bad_quaternion;
  }
  return std::nullopt;
}

}  // namespace twister::tracker::internal
