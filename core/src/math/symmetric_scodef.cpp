#include "twister/math/symmetric_scodef.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "twister/math/symmetry.hpp"
#include "twister/math/warp_plan.hpp"  // kCoincidentGrabFraction

namespace twister::math {

namespace {

// Pivots below this (the diagonal is near 1) mean two constraint rows are the same
// point, or a point and its image: no unique solution (as ScodefSystem).
constexpr double kSingularPivot = 1e-9;
// Above this condition number the system counts as singular too: the coefficients'
// rounding (about 1e-16 of their size) would move the constraint points by more than
// about 1e-8 of the motion.
constexpr double kMaxCondition = 1e8;

// Pi = (1/|S|) sum_{s in S} s: the orthogonal projection onto the fixed space of S.
glm::dmat3 projection(const SymmetryGroup& group, std::uint32_t stab) {
  glm::dmat3 sum(0.0);
  for (std::uint32_t bits = stab; bits != 0; bits &= bits - 1) {
    sum += group.element(static_cast<std::size_t>(std::countr_zero(bits)));
  }
  return sum / static_cast<double>(std::popcount(stab));
}

glm::dvec3 axis_of(const Frame& f, std::size_t j) { return j == 0 ? f.u : j == 1 ? f.v : f.w; }

}  // namespace

Status SymmetricScodef::add_constraint(const SymmetricWarp& warp, std::size_t member,
                                       glm::dvec3 c) {
  const SymmetryGroup& group = warp.group();
  const double same = kCoincidentGrabFraction * warp.radius();
  const std::size_t hand = member / kScodefConstraintsPerHand;
  for (std::size_t r = 0; r < reps_; ++r) {
    for (std::size_t g = 0; g < group.order(); ++g) {
      if (glm::length(group.element(g) * rep_[r] - c) > same) continue;
      // An image of a constraint point of the other hand: singular, as plain scodef.
      if (rep_hand_[r] != hand) return StatusCode::failed_precondition;
      member_rep_[member] = static_cast<std::uint8_t>(r);
      member_element_[member] = static_cast<std::uint8_t>(g);
      add_owners(warp, r, hand, g);
      return ok_status();
    }
  }
  // A new orbit: its stabiliser, and the point snapped onto the stabiliser's fixed set.
  std::uint32_t stab = 0;
  glm::dvec3 sum(0.0);
  for (std::size_t g = 0; g < group.order(); ++g) {
    const glm::dvec3 image = group.element(g) * c;
    if (glm::length(image - c) > same) continue;
    stab |= 1u << g;
    sum += image;
  }
  const std::size_t r = reps_++;
  rep_[r] = sum / static_cast<double>(std::popcount(stab));
  stab_[r] = stab;
  rep_hand_[r] = static_cast<std::uint8_t>(hand);
  member_rep_[member] = static_cast<std::uint8_t>(r);
  member_element_[member] = 0;
  add_owners(warp, r, hand, 0);
  return ok_status();
}

// The pairs (g, constraint) with g.c = rep are g = s a^-1, s in S_r (c = a.rep): each
// owned by the grab point g.O_hand.
void SymmetricScodef::add_owners(const SymmetricWarp& warp, std::size_t r, std::size_t hand,
                                 std::size_t a) {
  const SymmetryGroup& group = warp.group();
  const glm::dvec3 o = warp.start_frame(hand).origin;
  for (std::uint32_t bits = stab_[r]; bits != 0; bits &= bits - 1) {
    const auto s = static_cast<std::size_t>(std::countr_zero(bits));
    const glm::dvec3 owner = group.element(s) * (glm::transpose(group.element(a)) * o);
    std::size_t best = 0;
    for (std::size_t k = 1; k < warp.grab_point_count(); ++k) {
      if (glm::length(warp.grab_point(k) - owner) < glm::length(warp.grab_point(best) - owner)) {
        best = k;
      }
    }
    std::size_t i = 0;
    while (i < owner_len_[r] && owner_point_[r][i] != best) ++i;
    if (i == owner_len_[r]) {
      owner_point_[r][i] = static_cast<std::uint8_t>(best);
      owner_pairs_[r][i] = 0;
      ++owner_len_[r];
    }
    ++owner_pairs_[r][i];
    ++pairs_[r];
  }
}

double SymmetricScodef::basis(const SymmetricWarp& warp, std::size_t r, glm::dvec3 p) const {
  // One owner (the usual case): its squashed decay.
  if (owner_len_[r] == 1) return warp.squashed_decay(owner_point_[r][0], rep_[r], p);
  double sum = 0.0;
  for (std::size_t i = 0; i < owner_len_[r]; ++i) {
    sum += owner_pairs_[r][i] * warp.squashed_decay(owner_point_[r][i], rep_[r], p);
  }
  return sum / pairs_[r];
}

// Block (i, c) = (1/|S_c|) sum_g b_c(g^T rep_i) g, plus I - Pi_c on the diagonal (which
// holds A_c in the fixed space of S_c: the other blocks do not see the rest of it).
void SymmetricScodef::assemble(const SymmetricWarp& warp) {
  const SymmetryGroup& group = warp.group();
  for (std::size_t i = 0; i < reps_; ++i) {
    for (std::size_t c = 0; c < reps_; ++c) {
      glm::dmat3 m(0.0);
      for (std::size_t g = 0; g < group.order(); ++g) {
        const glm::dmat3& e = group.element(g);
        const double b = basis(warp, c, glm::transpose(e) * rep_[i]);
        if (b != 0.0) m += b * e;
      }
      m /= static_cast<double>(std::popcount(stab_[c]));
      if (i == c) m += glm::dmat3(1.0) - projection(group, stab_[c]);
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) {
          lu_[3 * i + static_cast<std::size_t>(row)][3 * c + static_cast<std::size_t>(col)] =
              m[col][row];
        }
      }
    }
  }
}

// Doolittle LU with partial pivoting, in place (as ScodefSystem).
Status SymmetricScodef::factorise() {
  const std::size_t n = 3 * reps_;
  for (std::size_t i = 0; i < n; ++i) perm_[i] = static_cast<std::uint8_t>(i);
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t best = k;
    for (std::size_t i = k + 1; i < n; ++i) {
      if (std::fabs(lu_[i][k]) > std::fabs(lu_[best][k])) best = i;
    }
    if (!(std::fabs(lu_[best][k]) > kSingularPivot)) return StatusCode::failed_precondition;
    std::swap(lu_[k], lu_[best]);
    std::swap(perm_[k], perm_[best]);
    for (std::size_t i = k + 1; i < n; ++i) {
      lu_[i][k] /= lu_[k][k];
      for (std::size_t j = k + 1; j < n; ++j) lu_[i][j] -= lu_[i][k] * lu_[k][j];
    }
  }
  return ok_status();
}

std::array<double, SymmetricScodef::kUnknowns> SymmetricScodef::substitute(
    const std::array<double, kUnknowns>& rhs) const {
  const std::size_t n = 3 * reps_;
  std::array<double, kUnknowns> x{};
  for (std::size_t i = 0; i < n; ++i) {
    double acc = rhs[perm_[i]];
    for (std::size_t j = 0; j < i; ++j) acc -= lu_[i][j] * x[j];
    x[i] = acc;
  }
  for (std::size_t i = n; i-- > 0;) {
    double acc = x[i];
    for (std::size_t j = i + 1; j < n; ++j) acc -= lu_[i][j] * x[j];
    x[i] = acc / lu_[i][i];
  }
  return x;
}

// The 1-norm condition number ||M||_1 ||M^-1||_1, the inverse column by column.
double SymmetricScodef::condition(double norm) const {
  const std::size_t n = 3 * reps_;
  double inverse = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    std::array<double, kUnknowns> e{};
    e[k] = 1.0;
    const std::array<double, kUnknowns> column = substitute(e);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += std::fabs(column[i]);
    inverse = std::max(inverse, sum);
  }
  return norm * inverse;
}

Status SymmetricScodef::build(const SymmetricWarp& warp) {
  built_ = false;
  reps_ = 0;
  coeff_ = {};
  pairs_ = {};
  owner_len_ = {};
  const double epsilon = kScodefEpsilonFraction * warp.radius();
  for (std::size_t h = 0; h < warp.hand_count(); ++h) {
    const Frame& f = warp.start_frame(h);
    for (std::size_t j = 0; j < kScodefConstraintsPerHand; ++j) {
      TWISTER_TRY(add_constraint(warp, h * kScodefConstraintsPerHand + j,
                                 f.origin + epsilon * axis_of(f, j)));
    }
  }
  assemble(warp);
  double norm = 0.0;
  for (std::size_t col = 0; col < 3 * reps_; ++col) {
    double sum = 0.0;
    for (std::size_t row = 0; row < 3 * reps_; ++row) sum += std::fabs(lu_[row][col]);
    norm = std::max(norm, sum);
  }
  TWISTER_TRY(factorise());
  // Clustered constraint points (a hand near a plane or an axis of high order: its
  // images close together) make the system ill-conditioned before any pivot is tiny;
  // its solution would then miss the targets (§11.8).
  if (!(condition(norm) <= kMaxCondition)) return StatusCode::failed_precondition;
  built_ = true;
  return ok_status();
}

// Where hand h's motion M(P) = O' + R (P - O) takes O + x, averaged over the conjugates
// s M s^-1 by the stabiliser S of its grab point O (§11.4's projection; M itself when S
// is trivial): (1/|S|) sum_s (s O' + s R s^T x), R x = U' (U.x) + V' (V.x) + W' (W.x).
glm::dvec3 SymmetricScodef::hand_target(const SymmetricWarp& warp, std::size_t h, glm::dvec3 x) {
  const Frame& a = warp.start_frame(h);
  const Frame& b = warp.end_frame(h);
  const auto turn = [&](glm::dvec3 v) {
    return glm::dot(a.u, v) * b.u + glm::dot(a.v, v) * b.v + glm::dot(a.w, v) * b.w;
  };
  if (warp.stabiliser_size(h) < 2) return b.origin + turn(x);
  const SymmetryGroup& group = warp.group();
  const double same = kCoincidentGrabFraction * warp.radius();
  glm::dvec3 sum(0.0);
  int n = 0;
  for (std::size_t g = 0; g < group.order(); ++g) {
    const glm::dmat3& s = group.element(g);
    if (glm::length(s * a.origin - a.origin) > same) continue;
    sum += s * (b.origin + turn(glm::transpose(s) * x));
    ++n;
  }
  return sum / static_cast<double>(n);
}

Status SymmetricScodef::solve(const SymmetricWarp& warp) {
  if (!built_) return StatusCode::failed_precondition;
  const SymmetryGroup& group = warp.group();
  const double epsilon = kScodefEpsilonFraction * warp.radius();
  // Each representative's target: the average of g.target over the pairs (g, c) with
  // g.c = rep, = Pi_r (1/m_r) sum_c a_c^T target(c).
  std::array<glm::dvec3, kMaxReps> sum{};
  std::array<int, kMaxReps> count{};
  for (std::size_t h = 0; h < warp.hand_count(); ++h) {
    for (std::size_t j = 0; j < kScodefConstraintsPerHand; ++j) {
      const std::size_t m = h * kScodefConstraintsPerHand + j;
      const glm::dvec3 target = hand_target(warp, h, epsilon * axis_of(warp.start_frame(h), j));
      sum[member_rep_[m]] += glm::transpose(group.element(member_element_[m])) * target;
      ++count[member_rep_[m]];
    }
  }
  std::array<double, kUnknowns> rhs{};
  for (std::size_t r = 0; r < reps_; ++r) {
    const glm::dvec3 t = projection(group, stab_[r]) * (sum[r] / static_cast<double>(count[r]));
    const glm::dvec3 d = t - rep_[r];
    rhs[3 * r] = d.x;
    rhs[3 * r + 1] = d.y;
    rhs[3 * r + 2] = d.z;
  }
  const std::array<double, kUnknowns> x = substitute(rhs);
  for (std::size_t r = 0; r < reps_; ++r) {
    coeff_[r] = projection(group, stab_[r]) * glm::dvec3(x[3 * r], x[3 * r + 1], x[3 * r + 2]);
  }
  return ok_status();
}

glm::dvec3 SymmetricScodef::displacement(const SymmetricWarp& warp, glm::dvec3 p) const {
  glm::dvec3 d(0.0);
  if (!built_) return d;
  const SymmetryGroup& group = warp.group();
  // A basis is 0 beyond r + e of its owner grab point (the squash only moves p away
  // from it), so beyond r + 2e of its constraint point.
  const double reach = (1.0 + 2.0 * kScodefEpsilonFraction) * warp.radius();
  for (std::size_t r = 0; r < reps_; ++r) {
    const double share = 1.0 / static_cast<double>(std::popcount(stab_[r]));
    for (std::size_t g = 0; g < group.order(); ++g) {
      const glm::dmat3& e = group.element(g);
      const glm::dvec3 q = g == 0 ? p : glm::transpose(e) * p;
      if (!(glm::length(q - rep_[r]) < reach)) continue;
      const double b = basis(warp, r, q);
      if (b != 0.0) d += (share * b) * (g == 0 ? coeff_[r] : e * coeff_[r]);
    }
  }
  return d;
}

bool SymmetricScodef::influences(const SymmetricWarp& warp, glm::dvec3 p) const {
  if (!built_) return false;
  const SymmetryGroup& group = warp.group();
  const double reach = (1.0 + 2.0 * kScodefEpsilonFraction) * warp.radius();
  for (std::size_t r = 0; r < reps_; ++r) {
    for (std::size_t g = 0; g < group.order(); ++g) {
      const glm::dvec3 q = glm::transpose(group.element(g)) * p;
      if (glm::length(q - rep_[r]) < reach && basis(warp, r, q) > 0.0) return true;
    }
  }
  return false;
}

}  // namespace twister::math
