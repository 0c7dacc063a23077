#include "twister/math/symmetry.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <numbers>
#include <optional>

#include "twister/math/decay.hpp"
#include "twister/math/warp_plan.hpp"  // kCoincidentGrabFraction

namespace twister::math {

namespace {

// Rotation by `angle` about coordinate axis a (columns: images of the basis vectors).
glm::dmat3 axis_rotation(int a, double angle) {
  const int b = (a + 1) % 3;
  const int c = (a + 2) % 3;
  const double co = std::cos(angle);
  const double si = std::sin(angle);
  glm::dmat3 m(0.0);
  m[a][a] = 1.0;
  m[b][b] = co;  // e_b -> co e_b + si e_c
  m[b][c] = si;
  m[c][b] = -si;  // e_c -> -si e_b + co e_c
  m[c][c] = co;
  return m;
}

}  // namespace

bool valid_symmetry(const SymmetrySpec& s) {
  switch (s.kind) {
    case SymmetryKind::none:
      return s.mirrors == 0 && s.axis == 0 && s.order == 0;
    case SymmetryKind::mirrors:
      return s.mirrors != 0 && (s.mirrors & ~(kMirrorX | kMirrorY | kMirrorZ)) == 0 &&
             s.axis == 0 && s.order == 0;
    case SymmetryKind::rotation:
    case SymmetryKind::rotation_mirror:
      return s.mirrors == 0 && s.axis <= 2 && s.order >= kMinRotationOrder &&
             s.order <= kMaxRotationOrder;
  }
  return false;
}

SymmetryGroup::SymmetryGroup() { set_none(); }

void SymmetryGroup::set_none() {
  elements_[0] = glm::dmat3(1.0);
  order_ = 1;
  spec_ = SymmetrySpec{};
}

Status SymmetryGroup::set(const SymmetrySpec& spec) {
  if (!valid_symmetry(spec)) return StatusCode::invalid_argument;
  switch (spec.kind) {
    case SymmetryKind::none:
      set_none();
      return ok_status();
    case SymmetryKind::mirrors:
      return set_mirrors(spec.mirrors);
    case SymmetryKind::rotation:
    case SymmetryKind::rotation_mirror:
      return set_rotation(spec.axis, spec.order, spec.kind == SymmetryKind::rotation_mirror);
  }
  return StatusCode::invalid_argument;
}

Status SymmetryGroup::set_mirrors(std::uint8_t planes) {
  if (planes == 0 || (planes & ~(kMirrorX | kMirrorY | kMirrorZ)) != 0) {
    return StatusCode::invalid_argument;
  }
  // Element i flips coordinate c when bit c of i is set; only subsets of `planes`.
  std::size_t n = 0;
  for (unsigned i = 0; i < 8; ++i) {
    if ((i & ~static_cast<unsigned>(planes)) != 0) continue;
    glm::dmat3 m(1.0);
    for (int c = 0; c < 3; ++c) {
      if ((i & (1u << c)) != 0) m[c][c] = -1.0;
    }
    elements_[n++] = m;
  }
  order_ = n;
  spec_ = SymmetrySpec{SymmetryKind::mirrors, planes, 0, 0};
  return ok_status();
}

Status SymmetryGroup::set_rotation(int axis, int n, bool with_mirror) {
  if (axis < 0 || axis > 2 || n < kMinRotationOrder || n > kMaxRotationOrder) {
    return StatusCode::invalid_argument;
  }
  const auto count = static_cast<std::size_t>(n);
  elements_[0] = glm::dmat3(1.0);
  for (std::size_t j = 1; j < count; ++j) {
    elements_[j] = axis_rotation(axis, 2.0 * std::numbers::pi * static_cast<double>(j) / n);
  }
  if (with_mirror) {
    // The reflection flipping the third coordinate c (the plane of a and b), then each
    // rotation: reflections in the planes through the axis at angles pi j / n.
    glm::dmat3 flip(1.0);
    const int c = (axis + 2) % 3;
    flip[c][c] = -1.0;
    for (std::size_t j = 0; j < count; ++j) elements_[count + j] = elements_[j] * flip;
  }
  order_ = with_mirror ? 2 * count : count;
  spec_ = SymmetrySpec{with_mirror ? SymmetryKind::rotation_mirror : SymmetryKind::rotation, 0,
                       static_cast<std::uint8_t>(axis), static_cast<std::uint8_t>(n)};
  return ok_status();
}

void SymmetricWarp::reset() {
  hands_ = 0;
  points_ = 0;
  scodef_.reset();
}

Status SymmetricWarp::build(const SymmetryGroup& group, std::span<const Frame> start, double radius,
                            WarpMethod method) {
  reset();
  if (start.empty() || start.size() > kMaxHands || !std::isfinite(radius) || !(radius > 0.0)) {
    return StatusCode::invalid_argument;
  }
  for (const Frame& f : start) {
    if (!is_orthonormal(f)) return StatusCode::invalid_argument;
  }
  const double same = kCoincidentGrabFraction * radius;
  const std::size_t order = group.order();
  std::size_t points = 0;
  for (std::size_t h = 0; h < start.size(); ++h) {
    // The stabiliser of the grab point, and the snap onto its fixed set (§11.4).
    const glm::dvec3 o = start[h].origin;
    glm::dvec3 sum(0.0);
    std::size_t stab = 0;
    for (std::size_t g = 0; g < order; ++g) {
      const glm::dvec3 image = g == 0 ? o : group.element(g) * o;
      if (glm::length(image - o) <= same) {
        sum += image;
        ++stab;
      }
    }
    start_[h] = start[h];
    if (stab > 1) start_[h].origin = sum / static_cast<double>(stab);
    shift_[h] = start_[h].origin - o;
    stab_[h] = stab;
    const std::size_t first_of_hand = points;
    for (std::size_t g = 0; g < order; ++g) {
      const glm::dvec3 image = g == 0 ? start_[h].origin : group.element(g) * start_[h].origin;
      std::size_t found = points;
      for (std::size_t k = 0; k < points; ++k) {
        if (glm::length(point_[k] - image) <= same) {
          found = k;
          break;
        }
      }
      if (found < first_of_hand) return StatusCode::invalid_argument;  // the other hand's
      if (found == points) point_[points++] = image;
      image_[h * SymmetryGroup::kMaxOrder + g] = static_cast<std::uint8_t>(found);
    }
  }
  for (std::size_t k = 0; k < points; ++k) {
    neighbours_[k] = 0;
    for (std::size_t j = 0; j < points; ++j) {
      if (j != k && glm::length(point_[j] - point_[k]) < radius) neighbours_[k] |= 1ull << j;
    }
  }
  group_ = group;
  points_ = points;
  radius_ = radius;
  method_ = method;
  hands_ = start.size();
  for (std::size_t h = 0; h < hands_; ++h) {
    end_[h] = start_[h];
    screws_[h] = compute_screw(start_[h], end_[h]);
  }
  if (method == WarpMethod::scodef) {
    const Status s = scodef_.build(*this);
    if (!s.ok()) {
      reset();
      return s;
    }
    return scodef_.solve(*this);
  }
  return ok_status();
}

Status SymmetricWarp::update(std::span<const Frame> end) { return set_end(end, true, 0); }

Status SymmetricWarp::update_turns(std::span<const Frame> end, std::uint8_t long_turns) {
  return set_end(end, false, long_turns);
}

Status SymmetricWarp::set_end(std::span<const Frame> end, bool keep_sense,
                              std::uint8_t long_turns) {
  if (!built()) return StatusCode::failed_precondition;
  if (end.size() != hands_) return StatusCode::invalid_argument;
  for (const Frame& f : end) {
    if (!is_orthonormal(f)) return StatusCode::invalid_argument;
  }
  for (std::size_t h = 0; h < hands_; ++h) {
    std::optional<glm::dvec3> previous;
    if (keep_sense && !screws_[h].pure_translation) previous = screws_[h].axis;
    end_[h] = end[h];
    if (stab_[h] > 1) end_[h].origin += shift_[h];
    screws_[h] = compute_screw(start_[h], end_[h], previous);
    if ((long_turns & (1u << h)) != 0) screws_[h] = long_way_round(screws_[h]);
  }
  return method_ == WarpMethod::scodef ? scodef_.solve(*this) : ok_status();
}

Status SymmetricWarp::rebase(std::span<const Frame> start) {
  if (!built()) return StatusCode::failed_precondition;
  if (start.size() != hands_) return StatusCode::invalid_argument;
  for (const Frame& f : start) {
    if (!is_orthonormal(f)) return StatusCode::invalid_argument;
  }
  if (method_ == WarpMethod::scodef) return rebase_scodef(start);
  for (std::size_t h = 0; h < hands_; ++h) {
    start_[h] = start[h];
    if (stab_[h] > 1) start_[h].origin += shift_[h];
    end_[h] = start_[h];
    screws_[h] = compute_screw(start_[h], end_[h]);
  }
  return ok_status();
}

// scodef's system at the new poses. A hand whose grab point was on a fixed set stays
// on it: its material there moved by the projection of the hand's motion (§11.4), to
// Pi (o + shift); the hand's frame is carried there by the new shift.
Status SymmetricWarp::rebase_scodef(std::span<const Frame> start) {
  std::array<Frame, kMaxHands> frames{};
  const double same = kCoincidentGrabFraction * radius_;
  for (std::size_t h = 0; h < hands_; ++h) {
    frames[h] = start[h];
    if (stab_[h] < 2) continue;
    const glm::dvec3 o = start[h].origin + shift_[h];
    glm::dvec3 sum(0.0);
    for (std::size_t g = 0; g < group_.order(); ++g) {
      const glm::dmat3& m = group_.element(g);
      if (glm::length(m * start_[h].origin - start_[h].origin) <= same) sum += m * o;
    }
    frames[h].origin = sum / static_cast<double>(stab_[h]);
  }
  SymmetricWarp next;
  TWISTER_TRY(next.build(group_, {frames.data(), hands_}, radius_, method_));
  for (std::size_t h = 0; h < hands_; ++h) {
    if (next.stab_[h] > 1) next.shift_[h] = next.start_[h].origin - start[h].origin;
  }
  *this = next;
  return ok_status();
}

double SymmetricWarp::squashed_decay(std::size_t k, glm::dvec3 centre, glm::dvec3 p) const {
  const glm::dvec3 grab = point_[k];
  std::uint64_t others = neighbours_[k];
  if (others == 0) return decay(glm::length(p - centre), radius_);
  double w = 1.0;
  while (others != 0 && w > 0.0) {
    const auto j = static_cast<std::size_t>(std::countr_zero(others));
    others &= others - 1;
    w = std::min(w,
                 decay(glm::length(squash_point(grab, point_[j], radius_, p) - centre), radius_));
  }
  return w;
}

bool SymmetricWarp::influences(glm::dvec3 p) const {
  if (method_ == WarpMethod::scodef) return scodef_.influences(*this, p);
  for (std::size_t k = 0; k < points_; ++k) {
    if (glm::length(p - point_[k]) < radius_) return true;
  }
  return false;
}

double SymmetricWarp::weight(std::size_t k, glm::dvec3 p) const {
  const glm::dvec3 grab = point_[k];
  std::uint64_t others = neighbours_[k];
  if (others == 0) return decay(glm::length(p - grab), radius_);
  // The squash only moves p away from the grab point (§11.3): beyond the radius every
  // term is decay(>= r) = 0, the value the loop below would reach.
  if (!(glm::length(p - grab) < radius_)) return 0.0;
  double w = 1.0;
  while (others != 0 && w > 0.0) {
    const auto j = static_cast<std::size_t>(std::countr_zero(others));
    others &= others - 1;
    w = std::min(w, decay(glm::length(squash_point(grab, point_[j], radius_, p) - grab), radius_));
  }
  return w;
}

glm::dvec3 SymmetricWarp::hand_move(std::size_t hand, double t, glm::dvec3 p) const {
  return method_ == WarpMethod::rottran ? rottran_at(screws_[hand], start_[hand], end_[hand], t, p)
                                        : screw_at(screws_[hand], t, p);
}

glm::dvec3 SymmetricWarp::warp_point(glm::dvec3 weights_at, glm::dvec3 p) const {
  if (!built()) return p;
  // scodef has no weights to keep: its system (rebuilt at each clutch step) at p.
  if (method_ == WarpMethod::scodef) return p + scodef_.displacement(*this, p);
  std::array<double, kMaxGrabPoints> w;
  for (std::size_t k = 0; k < points_; ++k) w[k] = weight(k, weights_at);
  glm::dvec3 moved = p;
  const std::size_t order = group_.order();
  for (std::size_t h = 0; h < hands_; ++h) {
    const double share = 1.0 / static_cast<double>(stab_[h]);
    for (std::size_t g = 0; g < order; ++g) {
      const double t = w[image_[h * SymmetryGroup::kMaxOrder + g]];
      if (t <= 0.0) continue;
      glm::dvec3 d;
      if (g == 0) {
        // The identity: exactly WarpPlan::warp_point's operations.
        d = hand_move(h, t, p) - p;
      } else {
        const glm::dmat3& m = group_.element(g);
        const glm::dvec3 q = glm::transpose(m) * p;
        d = m * (hand_move(h, t, q) - q);
      }
      if (stab_[h] > 1) d *= share;
      moved += d;
    }
  }
  return moved;
}

std::size_t symmetry_label(const SymmetrySpec& spec, std::span<char> out) {
  char text[kSymmetryLabelSize] = {};
  std::size_t n = 0;
  const auto put = [&](char c) {
    if (n + 1 < sizeof text) text[n++] = c;
  };
  switch (spec.kind) {
    case SymmetryKind::none:
      for (const char c : {'n', 'o', 'n', 'e'}) put(c);
      break;
    case SymmetryKind::mirrors:
      for (std::uint8_t axis = 0; axis < 3; ++axis) {
        if ((spec.mirrors & (1u << axis)) != 0) put(static_cast<char>('x' + axis));
      }
      break;
    case SymmetryKind::rotation:
    case SymmetryKind::rotation_mirror:
      for (const char c : {'r', 'o', 't'}) put(c);
      if (spec.order >= 10) put(static_cast<char>('0' + spec.order / 10));
      put(static_cast<char>('0' + spec.order % 10));
      if (spec.kind == SymmetryKind::rotation_mirror) put('m');
      put(' ');
      put(static_cast<char>('x' + (spec.axis % 3)));
      break;
  }
  if (out.empty()) return 0;
  const std::size_t written = n < out.size() ? n : out.size() - 1;
  for (std::size_t i = 0; i < written; ++i) out[i] = text[i];
  out[written] = '\0';
  return written;
}

}  // namespace twister::math
