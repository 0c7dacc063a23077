// SymmetricScodef: the scodef warp (docs/math.md §6) under a symmetry group (§11.8).
// The constraint points are every image of every hand's three points O + eU, O + eV,
// O + eW (coincident images merged); each image's target is the image of its hand's
// target (averaged where several images coincide). The solution is equivariant,
// A(g.c) = g.A(c), so only one representative per orbit is solved for: at most 6
// representatives, an 18 x 18 system factorised once per grab (LU, fixed storage).
// F(P) = P + sum_r (1/|S_r|) sum_g b_r(g^T P) g A_r, b_r the squashed basis of §11.8.
// Double precision, object frame, scene units. No heap, no exceptions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>

#include "twister/base/status.hpp"
#include "twister/math/scodef.hpp"

namespace twister::math {

class SymmetricWarp;

class SymmetricScodef {
 public:
  static constexpr std::size_t kMaxReps = kScodefMaxConstraints;
  static constexpr std::size_t kUnknowns = 3 * kMaxReps;
  // Grab points a SymmetricWarp can have (24 elements x 2 hands).
  static constexpr std::size_t kMaxOwners = 48;

  // The constraint points of `warp`'s (snapped) start frames and their images, and the
  // factorised system. failed_precondition: constraint points of different hands
  // coincide (within 1e-9 r, or under a group image), or the system is singular
  // (a pivot below 1e-9: constraint points too close to each other or to an image).
  Status build(const SymmetricWarp& warp);
  // The coefficients for `warp`'s end frames. failed_precondition: not built.
  Status solve(const SymmetricWarp& warp);
  void reset() { built_ = false; }

  // F(p) - p with the last solved coefficients (zero before solve()).
  glm::dvec3 displacement(const SymmetricWarp& warp, glm::dvec3 p) const;
  // True when some basis function (of some image) is non-zero at p.
  bool influences(const SymmetricWarp& warp, glm::dvec3 p) const;

  bool built() const { return built_; }
  // Orbit representatives (at most 3 per hand) and each one's position.
  std::size_t representative_count() const { return reps_; }
  glm::dvec3 representative(std::size_t r) const { return rep_[r]; }

 private:
  // b_r(p): the basis of representative r (its owners' squashed decays, averaged).
  double basis(const SymmetricWarp& warp, std::size_t r, glm::dvec3 p) const;
  Status add_constraint(const SymmetricWarp& warp, std::size_t member, glm::dvec3 c);
  void add_owners(const SymmetricWarp& warp, std::size_t r, std::size_t hand, std::size_t a);
  void assemble(const SymmetricWarp& warp);
  Status factorise();
  static glm::dvec3 hand_target(const SymmetricWarp& warp, std::size_t h, glm::dvec3 x);
  // x with M x = rhs (the factorised M).
  std::array<double, kUnknowns> substitute(const std::array<double, kUnknowns>& rhs) const;
  double condition(double norm) const;

  std::array<glm::dvec3, kMaxReps> rep_{};
  std::array<glm::dvec3, kMaxReps> coeff_{};
  std::array<std::uint32_t, kMaxReps> stab_{};  // bit g: element g fixes rep r
  std::array<std::uint8_t, kMaxReps> rep_hand_{};
  // Per original constraint (hand h, axis j): its representative and the element a
  // with c = a.rep.
  std::array<std::uint8_t, kMaxReps> member_rep_{};
  std::array<std::uint8_t, kMaxReps> member_element_{};
  // Per representative: the (element, constraint) pairs mapping onto it, by the grab
  // point that owns them (owner_len_ distinct ones: index, number of pairs); their total.
  std::array<std::array<std::uint8_t, kMaxOwners>, kMaxReps> owner_point_{};
  std::array<std::array<std::uint8_t, kMaxOwners>, kMaxReps> owner_pairs_{};
  std::array<std::uint8_t, kMaxReps> owner_len_{};
  std::array<std::uint16_t, kMaxReps> pairs_{};
  std::array<std::array<double, kUnknowns>, kUnknowns> lu_{};
  std::array<std::uint8_t, kUnknowns> perm_{};
  std::size_t reps_ = 0;
  bool built_ = false;
};

}  // namespace twister::math
