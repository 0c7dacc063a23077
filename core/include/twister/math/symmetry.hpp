// Symmetry: a finite group G of orthogonal maps of the object frame acting on the warp
// (docs/math.md §11). SymmetryGroup holds the group's matrices; SymmetricWarp evaluates
// the symmetrised warp F(P) = P + sum_h (1/|G_h|) sum_g g.(X_h(w, g^-1 P) - g^-1 P) per
// point in double, with the several-grab-point squash of §11.3, so F(gP) = gF(P).
// Double precision, world (object) frame, scene units. No heap, no exceptions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/status.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/symmetric_scodef.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::math {

enum class SymmetryKind : std::uint8_t {
  none,             // the trivial group
  mirrors,          // products of reflections in the chosen coordinate planes (2, 4, 8)
  rotation,         // Cn: n rotations about a coordinate axis
  rotation_mirror,  // Cnv: Cn and n reflections in planes containing the axis
};

// Bits of SymmetryGroup::mirrors: the plane x = 0 (reflection x -> -x), y = 0, z = 0.
inline constexpr std::uint8_t kMirrorX = 1;
inline constexpr std::uint8_t kMirrorY = 2;
inline constexpr std::uint8_t kMirrorZ = 4;
inline constexpr int kMinRotationOrder = 2;
inline constexpr int kMaxRotationOrder = 12;

// A group by its parameters (what the station's configuration, the journal and the live
// link carry): kind none; mirrors with the planes (kMirrorX/Y/Z bits); rotation or
// rotation_mirror with the axis (0 x, 1 y, 2 z) and the order n (2..12). Fields a kind
// does not use are 0 (canonical form, SymmetryGroup::spec()).
struct SymmetrySpec {
  SymmetryKind kind = SymmetryKind::none;
  std::uint8_t mirrors = 0;
  std::uint8_t axis = 0;
  std::uint8_t order = 0;
  friend bool operator==(const SymmetrySpec&, const SymmetrySpec&) = default;
};

// Whether `spec` names a group (canonical: unused fields 0).
bool valid_symmetry(const SymmetrySpec& spec);

// Longest label symmetry_label() writes, with its terminating zero.
inline constexpr std::size_t kSymmetryLabelSize = 16;
// Writes the group's name as the config names it ("none", "xy", "rot6 z", "rot6m z")
// into `out` (kSymmetryLabelSize: never truncated); returns the characters written
// (no zero counted). The station's log and the display's HUD both use it.
std::size_t symmetry_label(const SymmetrySpec& spec, std::span<char> out);

class SymmetryGroup {
 public:
  static constexpr std::size_t kMaxOrder = std::size_t{2} * kMaxRotationOrder;

  // The trivial group {I}.
  SymmetryGroup();

  // The group of the chosen planes (a non-zero combination of kMirrorX/Y/Z).
  // invalid_argument: planes == 0 or other bits set; the group is then unchanged.
  Status set_mirrors(std::uint8_t planes);
  // Cn (with_mirror false) or Cnv about the object frame's axis `axis` (0 x, 1 y, 2 z),
  // n in [2, 12]. invalid_argument otherwise; the group is then unchanged.
  Status set_rotation(int axis, int n, bool with_mirror);
  void set_none();
  // The group `spec` names; invalid_argument (group unchanged) unless valid_symmetry.
  Status set(const SymmetrySpec& spec);
  // The parameters of the group (canonical).
  SymmetrySpec spec() const { return spec_; }

  SymmetryKind kind() const { return spec_.kind; }
  std::size_t order() const { return order_; }
  bool trivial() const { return order_ == 1; }
  // Element i < order(); element 0 is the identity.
  const glm::dmat3& element(std::size_t i) const { return elements_[i]; }

 private:
  std::array<glm::dmat3, kMaxOrder> elements_{};
  std::size_t order_ = 1;
  SymmetrySpec spec_{};
};

class SymmetricWarp {
 public:
  static constexpr std::size_t kMaxHands = 2;
  static constexpr std::size_t kMaxGrabPoints = SymmetryGroup::kMaxOrder * kMaxHands;

  // Starts a grab under `group`: 1 or 2 orthonormal start frames, radius > 0, any
  // method (scodef: SymmetricScodef, §11.8). Grab points within 1e-9 r of their own
  // image are snapped onto the fixed set (§11.4); start and end origins move by the
  // same vector.
  // invalid_argument: wrong frame count, a frame not orthonormal, bad radius, or an
  //   image of one hand's grab point within 1e-9 r of the other's (§11.4).
  // failed_precondition: scodef's constraint system is singular (§11.8).
  // On error the warp is empty (identity).
  Status build(const SymmetryGroup& group, std::span<const Frame> start, double radius,
               WarpMethod method);
  // New end poses (same count as build); the minimal screw of each hand, keeping the
  // previous axis sense at a half turn as WarpPlan::update does (§2.3).
  // invalid_argument: wrong count or a frame not orthonormal; failed_precondition: not built.
  Status update(std::span<const Frame> end);
  // update() with each hand's screw chosen by the caller, as WarpPlan::update_turns:
  // the minimal screw of its poses (no sense carried over), the long way round where
  // bit h of `long_turns` is set.
  Status update_turns(std::span<const Frame> end, std::uint8_t long_turns);
  // A clutch step (WarpPlan::rebase): new start poses (each moved by its hand's snap),
  // identity screws, and the SAME grab points and weights (those of build). scodef
  // builds its system anew at the new poses (as WarpPlan does without a group), a hand
  // on a fixed set kept on it (§11.8); failed_precondition if that system is singular
  // (the warp is then unchanged).
  // invalid_argument: wrong count or a frame not orthonormal; failed_precondition: not built.
  Status rebase(std::span<const Frame> start);
  void reset();

  // F(p) of §11.2. Identity when not built.
  glm::dvec3 warp_point(glm::dvec3 p) const { return warp_point(p, p); }
  // One clutch-chain step at the current position q of a point whose weights come
  // from its chain-start position p: q + sum_h (1/|G_h|) sum_g g.(X_h(w_k(p), g^-1 q) -
  // g^-1 q). warp_point(p) is warp_point(p, p). Equivariant: F(gp, gq) = g F(p, q).
  glm::dvec3 warp_point(glm::dvec3 weights_at, glm::dvec3 q) const;
  // The weight w_k(p) of grab point k (§11.3).
  double weight(std::size_t k, glm::dvec3 p) const;
  // The same squash about grab point k, with the decay measured from `centre` instead
  // of the grab point: scodef's basis (§11.8). weight(k, p) = squashed_decay(k, P_k, p).
  double squashed_decay(std::size_t k, glm::dvec3 centre, glm::dvec3 p) const;
  // Whether the warp can move p: within the radius of a grab point, or (scodef) where
  // some basis is non-zero.
  bool influences(glm::dvec3 p) const;

  bool built() const { return hands_ > 0; }
  std::size_t hand_count() const { return hands_; }
  // The distinct grab points (all images of all hands, after snapping).
  std::size_t grab_point_count() const { return points_; }
  glm::dvec3 grab_point(std::size_t k) const { return point_[k]; }
  // Index of the grab point g.O_h (g = group element, h = hand).
  std::size_t grab_point_of(std::size_t hand, std::size_t element) const {
    return image_[hand * SymmetryGroup::kMaxOrder + element];
  }
  // |G_h|: how many elements fix hand h's grab point.
  std::size_t stabiliser_size(std::size_t hand) const { return stab_[hand]; }
  // The start frame of hand h after snapping, and its screw.
  const Frame& start_frame(std::size_t hand) const { return start_[hand]; }
  // The end frame of hand h after snapping (the last update; the start after build).
  const Frame& end_frame(std::size_t hand) const { return end_[hand]; }
  double radius() const { return radius_; }
  WarpMethod method() const { return method_; }
  const Screw& screw(std::size_t hand) const { return screws_[hand]; }
  const SymmetryGroup& group() const { return group_; }
  // The scodef system (built when method() is scodef).
  const SymmetricScodef& scodef() const { return scodef_; }

 private:
  glm::dvec3 hand_move(std::size_t hand, double t, glm::dvec3 p) const;
  Status set_end(std::span<const Frame> end, bool keep_sense, std::uint8_t long_turns);
  Status rebase_scodef(std::span<const Frame> start);

  SymmetryGroup group_{};
  std::array<glm::dvec3, kMaxGrabPoints> point_{};
  std::array<std::uint64_t, kMaxGrabPoints> neighbours_{};  // bit j: P_j in P_k's ball
  std::array<std::uint8_t, kMaxHands * SymmetryGroup::kMaxOrder> image_{};
  std::array<std::size_t, kMaxHands> stab_{};
  std::array<glm::dvec3, kMaxHands> shift_{};  // snap of §11.4 (0 unless stab_ > 1)
  std::array<Frame, kMaxHands> start_{};
  std::array<Frame, kMaxHands> end_{};
  std::array<Screw, kMaxHands> screws_{};
  std::size_t points_ = 0;
  std::size_t hands_ = 0;
  double radius_ = 1.0;
  WarpMethod method_ = WarpMethod::twister;
  SymmetricScodef scodef_{};
};

}  // namespace twister::math
