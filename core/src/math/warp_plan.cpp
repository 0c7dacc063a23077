#include "twister/math/warp_plan.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "twister/math/decay.hpp"

namespace twister::math {

namespace {
// Sparse selections are warped in chunks gathered onto the stack so the dense
// kernel can run on them unchanged.
constexpr std::size_t kGatherChunk = 256;

void put(double (&d)[3], glm::dvec3 v) {
  d[0] = v.x;
  d[1] = v.y;
  d[2] = v.z;
}

// Two grabs this close leave the squash undefined (docs/math.md §5).
bool coincident_grabs(std::span<const Frame> start, double radius) {
  return start.size() == 2 &&
         glm::length(start[1].origin - start[0].origin) <= kCoincidentGrabFraction * radius;
}

}  // namespace

// In place: returning the struct by value was miscompiled by GCC 12.2 at -O2 (IPA
// mod/ref dropped the stores into the member array); in-place is immune.
void fill_kernel_hand(KernelHand& h, const Screw& s, const Frame& start, const Frame& end,
                      WarpMethod method) {
  h = KernelHand{};
  put(h.axis, s.axis);
  if (method == WarpMethod::rottran) {
    put(h.mid, start.origin);
    put(h.shift, end.origin - start.origin);
    h.half_angle = s.pure_translation ? 0.0 : 0.5 * s.angle;
  } else if (s.pure_translation) {
    put(h.shift, s.chord);
  } else {
    put(h.mid, s.mid);
    put(h.chord, s.chord);
    put(h.axis_x_chord, glm::cross(s.axis, s.chord));
    put(h.shift, s.slide * s.axis);
    h.half_angle = 0.5 * s.angle;
    h.cot_half = s.cot_half;
  }
}
WarpPlan::WarpPlan(WarpPlanStorage storage)
    : indices_(storage.indices),
      weights1_(storage.weights1),
      weights2_(storage.weights2),
      symmetry_(storage.symmetry) {
  const std::size_t capacity = std::min({indices_.size(), weights1_.size(), weights2_.size()});
  indices_ = indices_.first(capacity);
  weights1_ = weights1_.first(capacity);
  weights2_ = weights2_.first(capacity);
}

void WarpPlan::reset() {
  if (symmetry_ != nullptr) {
    symmetry_->warp.reset();
    symmetry_->fast.reset();
  }
  hands_ = 0;
  long_turns_ = 0;
  count_ = 0;
  rest_size_ = 0;
  hand_counts_ = {};
  dense_ = false;
}

Status WarpPlan::check_frames(std::span<const Frame> frames) const {
  if (frames.size() != hands_) return StatusCode::invalid_argument;
  for (const Frame& f : frames) {
    if (!is_orthonormal(f)) return StatusCode::invalid_argument;
  }
  return ok_status();
}

double WarpPlan::weight_of(std::size_t hand, glm::dvec3 p) const {
  const glm::dvec3* other = hands_ == 2 ? &start_[1 - hand].origin : nullptr;
  return hand_weight(start_[hand].origin, other, radius_, p);
}

Status WarpPlan::build(ConstVertexColumns rest, std::span<const Frame> start, double radius,
                       WarpMethod method) {
  reset();
  if (start.empty() || start.size() > kMaxHands || !std::isfinite(radius) || !(radius > 0.0) ||
      !rest.consistent() || rest.size() > std::numeric_limits<std::uint32_t>::max()) {
    return StatusCode::invalid_argument;
  }
  for (const Frame& f : start) {
    if (!is_orthonormal(f)) return StatusCode::invalid_argument;
  }
  if (coincident_grabs(start, radius)) return StatusCode::invalid_argument;
  if (method == WarpMethod::scodef) TWISTER_TRY(scodef_.build(start, radius));

  radius_ = radius;
  method_ = method;
  hands_ = start.size();  // weight_of() needs the hands; reset() on failure below
  std::copy(start.begin(), start.end(), start_.begin());
  std::copy(start.begin(), start.end(), end_.begin());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 p(rest.x[i], rest.y[i], rest.z[i]);
    const double w1 = weight_of(0, p);
    const double w2 = hands_ == 2 ? weight_of(1, p) : 0.0;
    const bool moved =
        w1 > 0.0 || w2 > 0.0 || (method == WarpMethod::scodef && scodef_.influences(p));
    if (!moved) continue;
    if (count_ == capacity()) {
      reset();
      return StatusCode::resource_exhausted;
    }
    take(i, w1, w2);
  }
  finish_build(rest.size());
  if (method == WarpMethod::scodef) TWISTER_TRY(scodef_.solve(start));
  set_kernel_hands();
  return ok_status();
}

// Vertex i joins the plan with its weights (the caller checked the room).
void WarpPlan::take(std::size_t i, double w1, double w2) {
  indices_[count_] = static_cast<std::uint32_t>(i);
  weights1_[count_] = static_cast<float>(w1);
  weights2_[count_] = static_cast<float>(w2);
  if (w1 > 0.0) ++hand_counts_[0];
  if (w2 > 0.0) ++hand_counts_[1];
  ++count_;
}

// After the vertices: the rest size, whether they are one run, each hand's screw.
void WarpPlan::finish_build(std::size_t rest_size) {
  rest_size_ = rest_size;
  dense_ = count_ == 0 || indices_[count_ - 1] - indices_[0] == count_ - 1;
  for (std::size_t h = 0; h < hands_; ++h) screws_[h] = compute_screw(start_[h], end_[h]);
}

Status WarpPlan::build(ConstVertexColumns rest, std::span<const Frame> start, double radius,
                       WarpMethod method, const SymmetryGroup& group) {
  if (group.trivial()) return build(rest, start, radius, method);
  const Status s = build_symmetric(rest, start, radius, method, group);
  if (!s.ok()) reset();
  return s;
}

Status WarpPlan::build_symmetric(ConstVertexColumns rest, std::span<const Frame> start,
                                 double radius, WarpMethod method, const SymmetryGroup& group) {
  reset();
  if (symmetry_ == nullptr) return StatusCode::failed_precondition;
  if (!rest.consistent() || rest.size() > std::numeric_limits<std::uint32_t>::max() ||
      coincident_grabs(start, radius)) {
    return StatusCode::invalid_argument;
  }
  // The frame, radius and method checks, the snap and the images (§11.4).
  SymmetricWarp& sym = symmetry_->warp;
  TWISTER_TRY(sym.build(group, start, radius, method));
  radius_ = radius;
  method_ = method;
  hands_ = start.size();
  std::copy(start.begin(), start.end(), start_.begin());
  std::copy(start.begin(), start.end(), end_.begin());
  const VertexColumns& keep = symmetry_->start;
  const std::size_t room = std::min({capacity(), keep.x.size(), keep.y.size(), keep.z.size()});
  // scodef has no float path (§11.8): apply() runs it per vertex in double.
  const bool scodef = method == WarpMethod::scodef;
  SymmetricFloat& fast = symmetry_->fast;
  if (!scodef) fast.begin(sym, symmetry_->balls, symmetry_->weights, room);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 p(rest.x[i], rest.y[i], rest.z[i]);
    // Weights vanish beyond the radius of every grab point (the squash only lowers them);
    // the vertex joins the float path's ball of each grab point that reaches it.
    if (count_ == room) {
      if (sym.influences(p)) return StatusCode::resource_exhausted;
      continue;
    }
    if (scodef ? !sym.influences(p) : !fast.reaches(sym, p)) continue;
    // The display's weights: each hand's own grab point (the identity image).
    const double w1 = sym.weight(sym.grab_point_of(0, 0), p);
    const double w2 = hands_ == 2 ? sym.weight(sym.grab_point_of(1, 0), p) : 0.0;
    keep.x[count_] = rest.x[i];
    keep.y[count_] = rest.y[i];
    keep.z[count_] = rest.z[i];
    take(i, w1, w2);
  }
  if (!scodef) fast.finish(sym, keep, {indices_.data(), count_});
  finish_build(rest.size());
  set_kernel_hands();
  return ok_status();
}

Status WarpPlan::update(std::span<const Frame> end) { return set_end(end, true, 0); }

Status WarpPlan::update_turns(std::span<const Frame> end, std::uint8_t long_turns) {
  return set_end(end, false, long_turns);
}

Status WarpPlan::set_end(std::span<const Frame> end, bool keep_sense, std::uint8_t long_turns) {
  if (!built()) return StatusCode::failed_precondition;
  TWISTER_TRY(check_frames(end));
  if (method_ == WarpMethod::scodef && !symmetric()) TWISTER_TRY(scodef_.solve(end));
  if (symmetric()) {
    TWISTER_TRY(keep_sense ? symmetry_->warp.update(end)
                           : symmetry_->warp.update_turns(end, long_turns));
  }
  for (std::size_t h = 0; h < hands_; ++h) {
    std::optional<glm::dvec3> previous;
    if (keep_sense && !screws_[h].pure_translation) previous = screws_[h].axis;
    screws_[h] = compute_screw(start_[h], end[h], previous);
    if ((long_turns & (1u << h)) != 0) screws_[h] = long_way_round(screws_[h]);
    end_[h] = end[h];
  }
  long_turns_ = static_cast<std::uint8_t>(long_turns & ((1u << hands_) - 1u));
  set_kernel_hands();
  return ok_status();
}

Status WarpPlan::rebase(std::span<const Frame> start) {
  if (!built()) return StatusCode::failed_precondition;
  TWISTER_TRY(check_frames(start));
  if (coincident_grabs(start, radius_)) return StatusCode::invalid_argument;
  if (method_ == WarpMethod::scodef && !symmetric()) {
    ScodefSystem fresh;
    TWISTER_TRY(fresh.build(start, radius_));
    TWISTER_TRY(fresh.solve(start));
    scodef_ = fresh;
  }
  // Symmetric: the same grab points and weights (of the chain-start positions).
  if (symmetric()) {
    TWISTER_TRY(symmetry_->warp.rebase(start));
    symmetry_->fast.rebased();
  }
  for (std::size_t h = 0; h < hands_; ++h) {
    start_[h] = start[h];
    end_[h] = start[h];
    screws_[h] = compute_screw(start_[h], end_[h]);
  }
  long_turns_ = 0;
  set_kernel_hands();
  return ok_status();
}

void WarpPlan::set_kernel_hands() {
  for (std::size_t h = 0; h < hands_; ++h) {
    fill_kernel_hand(kernel_hands_[h], screws_[h], start_[h], end_[h], method_);
  }
}

std::span<const float> WarpPlan::weights(std::size_t hand) const {
  if (hand >= hands_) return {};
  return {hand == 0 ? weights1_.data() : weights2_.data(), count_};
}

std::size_t WarpPlan::influenced_count(std::size_t hand) const {
  return hand < hands_ ? hand_counts_[hand] : 0;
}

Status WarpPlan::apply(ConstVertexColumns rest, VertexColumns out) const {
  if (!built()) return StatusCode::failed_precondition;
  if (!rest.consistent() || !out.consistent() || rest.size() != rest_size_ ||
      out.size() != rest_size_) {
    return StatusCode::invalid_argument;
  }
  if (count_ == 0) return ok_status();
  if (symmetric()) {
    const PlanSymmetry& sym = *symmetry_;
    if (kernel_ == KernelKind::simd && sym.fast.ready()) {
      sym.fast.apply(sym.warp, sym.start, rest, out);
    } else {
      apply_symmetric(rest, out);
    }
    return ok_status();
  }
  if (method_ == WarpMethod::scodef) {
    // Not the hot path (a comparison method): evaluated per point in double.
    for (std::size_t i = 0; i < count_; ++i) {
      const std::uint32_t v = indices_[i];
      const glm::dvec3 p(rest.x[v], rest.y[v], rest.z[v]);
      const glm::dvec3 q = p + scodef_.displacement(p);
      out.x[v] = static_cast<float>(q.x);
      out.y[v] = static_cast<float>(q.y);
      out.z[v] = static_cast<float>(q.z);
    }
    return ok_status();
  }
  const auto run = [this](const KernelSpan& s) {
    const bool two = hands_ == 2;
    if (kernel_ == KernelKind::simd) {
      two ? warp_two_simd(kernel_hands_[0], kernel_hands_[1], s)
          : warp_one_simd(kernel_hands_[0], s);
    } else {
      two ? warp_two_scalar(kernel_hands_[0], kernel_hands_[1], s)
          : warp_one_scalar(kernel_hands_[0], s);
    }
  };
  if (dense_) {
    const std::size_t first = indices_[0];
    run(KernelSpan{rest.x.data() + first, rest.y.data() + first, rest.z.data() + first,
                   weights1_.data(), weights2_.data(), out.x.data() + first, out.y.data() + first,
                   out.z.data() + first, count_});
    return ok_status();
  }
  float gx[kGatherChunk];
  float gy[kGatherChunk];
  float gz[kGatherChunk];
  float rx[kGatherChunk];
  float ry[kGatherChunk];
  float rz[kGatherChunk];
  for (std::size_t base = 0; base < count_; base += kGatherChunk) {
    const std::size_t n = std::min(kGatherChunk, count_ - base);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = indices_[base + i];
      gx[i] = rest.x[v];
      gy[i] = rest.y[v];
      gz[i] = rest.z[v];
    }
    run(KernelSpan{gx, gy, gz, weights1_.data() + base, weights2_.data() + base, rx, ry, rz, n});
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t v = indices_[base + i];
      out.x[v] = rx[i];
      out.y[v] = ry[i];
      out.z[v] = rz[i];
    }
  }
  return ok_status();
}

void WarpPlan::apply_symmetric(ConstVertexColumns rest, VertexColumns out) const {
  // Not the float kernels: every image of every hand per vertex, in double (§11.2).
  // The weights come from the chain-start position (the rest position at step 0).
  const SymmetricWarp& sym = symmetry_->warp;
  const VertexColumns& keep = symmetry_->start;
  const SymmetricFloat& fast = symmetry_->fast;
  for (std::size_t i = 0; i < count_; ++i) {
    // The chain-start columns are in the float path's sorted order once it is built.
    const std::uint32_t v = fast.ready() ? fast.vertex(i) : indices_[i];
    const glm::dvec3 p(keep.x[i], keep.y[i], keep.z[i]);
    const glm::dvec3 q(rest.x[v], rest.y[v], rest.z[v]);
    const glm::dvec3 moved = sym.warp_point(p, q);
    out.x[v] = static_cast<float>(moved.x);
    out.y[v] = static_cast<float>(moved.y);
    out.z[v] = static_cast<float>(moved.z);
  }
}

glm::dvec3 WarpPlan::warp_point(glm::dvec3 p) const {
  if (!built()) return p;
  if (symmetric()) return symmetry_->warp.warp_point(p);
  if (method_ == WarpMethod::scodef) return p + scodef_.displacement(p);
  glm::dvec3 moved = p;
  for (std::size_t h = 0; h < hands_; ++h) {
    const double t = weight_of(h, p);
    if (t <= 0.0) continue;
    const glm::dvec3 q = method_ == WarpMethod::rottran
                             ? rottran_at(screws_[h], start_[h], end_[h], t, p)
                             : screw_at(screws_[h], t, p);
    moved += q - p;
  }
  return moved;
}

namespace {

// hand_weight in float over n points: squash towards the other grab, then decay.
void float_weights(const Frame& grab, const Frame* other, double radius, const float* x,
                   const float* y, const float* z, float* w, std::size_t n) {
  const float g[3] = {static_cast<float>(grab.origin.x), static_cast<float>(grab.origin.y),
                      static_cast<float>(grab.origin.z)};
  float u[3] = {0.0f, 0.0f, 0.0f};
  float stretch = 0.0f;  // (r - s) / s along the unit OQ, 0: no squash
  if (other != nullptr) {
    const glm::dvec3 oq = other->origin - grab.origin;
    const double s = glm::length(oq);
    if (s < radius && s > 0.0) {
      u[0] = static_cast<float>(oq.x / s);
      u[1] = static_cast<float>(oq.y / s);
      u[2] = static_cast<float>(oq.z / s);
      stretch = static_cast<float>((radius - s) / s);
    }
  }
  decay_weights_simd(DecaySpan{x, y, z, w, n}, g, u, stretch, static_cast<float>(radius));
}

}  // namespace

bool WarpPlan::warp_points_float(const float* x, const float* y, const float* z, float* out_x,
                                 float* out_y, float* out_z, std::size_t n) const {
  if (!built() || method_ == WarpMethod::scodef || n > kFloatChunk) return false;
  if (symmetric()) {
    symmetry_->fast.warp_points(symmetry_->warp, x, y, z, out_x, out_y, out_z, n);
    return true;
  }
  float w1[kFloatChunk];
  float w2[kFloatChunk];
  const bool two = hands_ == 2;
  float_weights(start_[0], two ? &start_[1] : nullptr, radius_, x, y, z, w1, n);
  if (two) float_weights(start_[1], &start_[0], radius_, x, y, z, w2, n);
  // A batch that only one hand reaches (the usual case: the points of one edge
  // region lie together) takes that hand's kernel: half the arithmetic, within the
  // same bound (float_error_bound sums the hands'). "Reaches": a weight above 2^-30;
  // the float decay leaves ~1e-14 outside the radius, and dropping a weight that small
  // stays inside the bound's weight term (2^-18 for ~2^-19 of arithmetic error).
  const auto reached = [n](const float* w) {
    float most = 0.0f;
    for (std::size_t i = 0; i < n; ++i) most = std::max(most, w[i]);
    return most > 0x1p-30f;
  };
  if (two && !reached(w2)) {
    warp_one_simd(kernel_hands_[0], KernelSpan{x, y, z, w1, w1, out_x, out_y, out_z, n});
  } else if (two && !reached(w1)) {
    warp_one_simd(kernel_hands_[1], KernelSpan{x, y, z, w2, w2, out_x, out_y, out_z, n});
  } else {
    const KernelSpan s{x, y, z, w1, two ? w2 : w1, out_x, out_y, out_z, n};
    two ? warp_two_simd(kernel_hands_[0], kernel_hands_[1], s) : warp_one_simd(kernel_hands_[0], s);
  }
  return true;
}

// Forward error analysis (docs/refinement.md "The float filter"), u = 2^-24:
//  - the weight: squash, length, the polynomial cos and its square in float give
//    |t_f - t| <= ~40 u (relative errors of a few u in d, the argument's pi/2 scale,
//    6e-9 from the polynomial, doubled by the square); taken as 2^-18 (64 u);
//  - the kernel's arithmetic (~45 float operations per hand, every intermediate at most
//    the hand's magnitude A = |p| + |M| + |k X| + |T| + 2 V, V = r + |grab - M| the
//    farthest point it moves, F and G rounded to float, the polynomial sin/cos at
//    4e-8): |error| <= ~50 u A per hand; taken as 2^-16 A (256 u A);
//  - the weight error moves the point by at most |dD/dt| |t_f - t| with
//    |dD/dt| <= G = 2 (a/2) (2 V + |k X|) + |T|;
//  - output rounding: 2^-23 extent;
//  - the point itself may be off by 2^-23 extent (a float midpoint): times the warp's
//    Lipschitz bound L = 1 + sum (4 + G |grad t|), |grad t| <= pi/(2r) max(1, r/s)
//    (s: the distance between the grabs, the squash's stretch).
double WarpPlan::float_error_bound(double extent_m) const {
  if (!built() || method_ == WarpMethod::scodef) return std::numeric_limits<double>::infinity();
  if (symmetric()) return symmetry_->fast.error_bound(symmetry_->warp, extent_m);
  constexpr double kWeight = 0x1p-18;
  constexpr double kKernel = 0x1p-16;
  double bound = 0x1p-23 * 1.7320508075688772 * extent_m;
  double lipschitz = 1.0;
  const double s = hands_ == 2 ? glm::length(start_[1].origin - start_[0].origin) : radius_;
  const double stretch = s > 0.0 && s < radius_ ? radius_ / s : 1.0;
  for (std::size_t h = 0; h < hands_; ++h) {
    const KernelHand& k = kernel_hands_[h];
    const glm::dvec3 mid(k.mid[0], k.mid[1], k.mid[2]);
    const double kx =
        std::abs(k.cot_half) * glm::length(glm::dvec3(k.chord[0], k.chord[1], k.chord[2]));
    const double shift = glm::length(glm::dvec3(k.shift[0], k.shift[1], k.shift[2]));
    const double v = radius_ + glm::length(start_[h].origin - mid);
    const double magnitude = 1.7320508075688772 * extent_m + glm::length(mid) + kx + shift + 2 * v;
    const double slope = 2.0 * std::abs(k.half_angle) * (2.0 * v + kx) + shift;
    bound += kKernel * magnitude + kWeight * slope;
    lipschitz += 4.0 + slope * 0.5 * 3.14159265358979324 / radius_ * stretch;
  }
  return bound + 0x1p-23 * 1.7320508075688772 * extent_m * lipschitz;
}

}  // namespace twister::math
