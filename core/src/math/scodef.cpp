#include "twister/math/scodef.hpp"

#include <cmath>
#include <glm/geometric.hpp>

#include "twister/math/decay.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::math {

namespace {
// Pivots below this (entries are in [0, 1], the diagonal near 1) mean two
// constraint rows are the same point: the system has no unique solution.
constexpr double kSingularPivot = 1e-9;

void constraint_points(const Frame& f, double eps, glm::dvec3* out) {
  out[0] = f.origin + eps * f.u;
  out[1] = f.origin + eps * f.v;
  out[2] = f.origin + eps * f.w;
}
}  // namespace

double ScodefSystem::basis(std::size_t j, glm::dvec3 p) const {
  const std::size_t h = j / kScodefConstraintsPerHand;
  const glm::dvec3 q = hands_ == 2 ? squash_point(grab_[h], grab_[1 - h], radius_, p) : p;
  return decay(glm::length(q - points_[j]), radius_);
}

Status ScodefSystem::build(std::span<const Frame> start, double radius) {
  built_ = false;
  coeffs_ = {};
  if (start.empty() || start.size() > 2 || !std::isfinite(radius) || !(radius > 0.0)) {
    return StatusCode::invalid_argument;
  }
  hands_ = start.size();
  count_ = hands_ * kScodefConstraintsPerHand;
  radius_ = radius;
  epsilon_ = kScodefEpsilonFraction * radius;
  for (std::size_t h = 0; h < hands_; ++h) {
    grab_[h] = start[h].origin;
    constraint_points(start[h], epsilon_, &points_[h * kScodefConstraintsPerHand]);
  }
  if (hands_ == 2 && glm::length(grab_[1] - grab_[0]) <= kCoincidentGrabFraction * radius) {
    return StatusCode::invalid_argument;
  }
  for (std::size_t i = 0; i < count_; ++i) {
    for (std::size_t j = 0; j < count_; ++j) lu_[i][j] = basis(j, points_[i]);
    perm_[i] = i;
  }
  // Doolittle LU with partial pivoting, in place.
  for (std::size_t k = 0; k < count_; ++k) {
    std::size_t best = k;
    for (std::size_t i = k + 1; i < count_; ++i) {
      if (std::fabs(lu_[i][k]) > std::fabs(lu_[best][k])) best = i;
    }
    if (!(std::fabs(lu_[best][k]) > kSingularPivot)) return StatusCode::failed_precondition;
    std::swap(lu_[k], lu_[best]);
    std::swap(perm_[k], perm_[best]);
    for (std::size_t i = k + 1; i < count_; ++i) {
      lu_[i][k] /= lu_[k][k];
      for (std::size_t j = k + 1; j < count_; ++j) lu_[i][j] -= lu_[i][k] * lu_[k][j];
    }
  }
  built_ = true;
  return ok_status();
}

Status ScodefSystem::solve(std::span<const Frame> end) {
  if (!built_) return StatusCode::failed_precondition;
  if (end.size() != hands_) return StatusCode::invalid_argument;
  std::array<glm::dvec3, kScodefMaxConstraints> target{};
  for (std::size_t h = 0; h < hands_; ++h) {
    constraint_points(end[h], epsilon_, &target[h * kScodefConstraintsPerHand]);
  }
  std::array<glm::dvec3, kScodefMaxConstraints> y{};
  for (std::size_t i = 0; i < count_; ++i) {
    const std::size_t row = perm_[i];
    glm::dvec3 acc = target[row] - points_[row];
    for (std::size_t j = 0; j < i; ++j) acc -= lu_[i][j] * y[j];
    y[i] = acc;
  }
  for (std::size_t i = count_; i-- > 0;) {
    glm::dvec3 acc = y[i];
    for (std::size_t j = i + 1; j < count_; ++j) acc -= lu_[i][j] * coeffs_[j];
    coeffs_[i] = acc / lu_[i][i];
  }
  return ok_status();
}

glm::dvec3 ScodefSystem::displacement(glm::dvec3 p) const {
  glm::dvec3 d(0.0);
  if (!built_) return d;
  for (std::size_t j = 0; j < count_; ++j) {
    const double b = basis(j, p);
    if (b != 0.0) d += b * coeffs_[j];
  }
  return d;
}

bool ScodefSystem::influences(glm::dvec3 p) const {
  if (!built_) return false;
  for (std::size_t j = 0; j < count_; ++j) {
    if (basis(j, p) > 0.0) return true;
  }
  return false;
}

}  // namespace twister::math
