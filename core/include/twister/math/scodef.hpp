// ScodefSystem: the `scodef` alternative (docs/math.md §6, Borrel and Rappoport 1994) for
// one or two hands. Per hand three constraint points O + eU, O + eV, O + eW
// (e = 0.1 r) move to O' + eU', O' + eV', O' + eW'; the basis of a constraint of
// hand h at point P is phi(sigma_h(P) - O_j), phi(X) = cos^2((pi/2)|X|/r) for
// |X| < r, where sigma_h is hand h's squash map of §5 (identity without squash),
// so scodef gets the same decay and squash as the other methods.
// F(P) = P + sum_j phi_j(P) A_j, with A solved from F(O_i) = O'_i.
// Double precision, world frame, scene units. No heap: fixed 6x6 system.
#pragma once

#include <array>
#include <cstddef>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/status.hpp"
#include "twister/math/frame.hpp"

namespace twister::math {

inline constexpr std::size_t kScodefConstraintsPerHand = 3;
inline constexpr std::size_t kScodefMaxConstraints = 2 * kScodefConstraintsPerHand;
inline constexpr double kScodefEpsilonFraction = 0.1;  // e = 0.1 r

class ScodefSystem {
 public:
  // Sets up and factorises the constraint matrix for 1 or 2 start frames.
  // invalid_argument: no/too many frames, radius <= 0 or not finite, or the two
  //   grab points coincide (squash undefined).
  // failed_precondition: the constraint matrix is singular (two constraint points
  //   of different hands coincide); the system is left unusable.
  Status build(std::span<const Frame> start, double radius);

  // Solves for the coefficients A_j from the end frames (same count as build).
  // invalid_argument: wrong frame count; failed_precondition: not built.
  Status solve(std::span<const Frame> end);

  // F(P) - P with the last solved coefficients (zero before solve()).
  glm::dvec3 displacement(glm::dvec3 p) const;

  // True when some basis function is non-zero at p (p is moved by the warp).
  bool influences(glm::dvec3 p) const;

  bool built() const { return built_; }
  std::size_t constraint_count() const { return count_; }

 private:
  double basis(std::size_t j, glm::dvec3 p) const;

  std::array<glm::dvec3, kScodefMaxConstraints> points_{};
  std::array<glm::dvec3, kScodefMaxConstraints> coeffs_{};
  // LU factors of the constraint matrix with partial pivoting (row permutation).
  std::array<std::array<double, kScodefMaxConstraints>, kScodefMaxConstraints> lu_{};
  std::array<std::size_t, kScodefMaxConstraints> perm_{};
  std::array<glm::dvec3, 2> grab_{};
  std::size_t count_ = 0;
  std::size_t hands_ = 0;
  double radius_ = 1.0;
  double epsilon_ = 0.1;
  bool built_ = false;
};

}  // namespace twister::math
