// Symmetry cues (issue 26): where a symmetric stroke acts besides the hands. For the
// group shown (the open stroke's, else the station's next-stroke group from its
// status), each present hand's images g(hand) for every non-identity element g get a
// ghost cursor (a smaller ball in a light tint of the hand's colour, always on top)
// and a ghost frame glyph (the hand's axes under g, thin); the mirror planes are drawn
// as faint squares through the object frame's origin and a rotation's axis as a faint
// tube. Object frame in, world frame out (through `model`), sizes from the model's
// bounding radius, as the other cues (cue_geometry.hpp).
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

#include "cue_geometry.hpp"
#include "scene_replica.hpp"
#include "twister/math/symmetry.hpp"

namespace twister::bridge {

// Ghost cursor colours (hand 1, hand 2): the hands' red and green, lightened.
inline constexpr glm::vec4 kGhostHand0{1.0F, 0.62F, 0.62F, 1.0F};
inline constexpr glm::vec4 kGhostHand1{0.62F, 1.0F, 0.62F, 1.0F};

// The group the display shows: the open stroke's while one is drawn, else the
// station's next-stroke group (status), else none.
math::SymmetrySpec shown_symmetry(const SceneReplica& replica);

struct GhostCursor {
  std::size_t hand = 0;     // session hand
  glm::dvec3 position{};    // object frame: g(hand origin)
  glm::dmat3 element{1.0};  // g
};
// Every present hand's images under `spec`'s non-identity elements (object frame); an
// image that falls on the hand itself (a hand on a mirror plane or the axis) is left out.
std::vector<GhostCursor> ghost_cursors(const SceneReplica& replica, const math::SymmetrySpec& spec);

// Adds the ghosts, planes and axis of shown_symmetry() to `out` (with the glyph cues).
void add_symmetry_cues(const SceneReplica& replica, const glm::mat4& model, float scene_radius_m,
                       CueScene& out);

// A group by the station's config names ("none", "x", "xz", "rot6 z", "rot6m y").
std::string symmetry_name(const math::SymmetrySpec& spec);

// The HUD's line naming the group: "symmetry: rot6 z (this stroke)" or "(next strokes)";
// empty without a group (none, or before the station's first status and no stroke).
std::string symmetry_hud_line(const SceneReplica& replica);

}  // namespace twister::bridge
