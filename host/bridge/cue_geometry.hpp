// The paper's cues as triangle geometry (no GL: built on the CPU each frame from
// the replica's data, in the world frame, drawn by CueRenderer):
//   - each present hand: a frame glyph (its U, V, W axes in red, green, blue) and a
//     cursor ball in the hand's colour (red hand 1, green hand 2) at its origin;
//   - each present hand: a translucent sphere of influence of the session's
//     radius, squashed where the two balls overlap exactly as the station's weights
//     are (core math::hand_weight, searched along each direction);
//   - during a stroke, per stroke hand: the screw axis as a pink cylinder and the
//     grab point's trajectory from rest to now as a yellow tube (core
//     math::screw_at; rottran_at for rottran; none for scodef, which has no screw);
//   - while a hand holds move-object: the object frame (larger RGB axes);
//   - under a symmetry group (with the glyphs): ghost cursors and glyphs at the hands'
//     images, the mirror planes or the rotation axis, lightly (symmetry_cues.hpp).
// Sizes scale with the model's bounding radius (`scene_radius_m`).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "scene_replica.hpp"

namespace twister::bridge {

inline constexpr glm::vec4 kAxisPink{1.0F, 0.41F, 0.71F, 1.0F};
inline constexpr glm::vec4 kTrajectoryYellow{1.0F, 0.86F, 0.08F, 1.0F};

// Triangles with a colour per vertex (RGBA), world frame.
struct CueMesh {
  std::vector<float> positions;  // x y z per vertex
  std::vector<float> colours;    // r g b a per vertex
  std::vector<std::uint32_t> indices;

  void clear();
  std::size_t vertex_count() const { return positions.size() / 3; }
  // A closed cylinder from a to b (nothing when a == b).
  void add_tube(glm::vec3 a, glm::vec3 b, float radius, glm::vec4 colour, int sides = 10);
  // A ball whose surface point in direction d lies at centre + extent(d) * d.
  template <typename Extent>
  void add_ball(glm::vec3 centre, glm::vec4 colour, int rings, int segments, Extent extent);
  void add_sphere(glm::vec3 centre, float radius, glm::vec4 colour, int rings = 10,
                  int segments = 16) {
    add_ball(centre, colour, rings, segments, [radius](glm::vec3) { return radius; });
  }
};

struct CueScene {
  CueMesh lines;        // glyph axes, screw axes, trajectories, object frame: hidden parts fade
  CueMesh translucent;  // spheres of influence
  CueMesh overlay;      // hand cursors: always on top
};

struct CueOptions {
  bool glyphs = true;
  bool spheres = true;
  bool screw_axes = true;
  bool trajectories = true;
  bool object_frame = true;
};

// A point of the object frame in the world (`model`: the renderer's model matrix).
inline glm::vec3 to_world(const glm::mat4& model, glm::dvec3 p) {
  return glm::vec3(model * glm::vec4(glm::vec3(p), 1.0F));
}

// A direction of the object frame in the world.
inline glm::vec3 turn(const glm::mat4& model, glm::dvec3 d) {
  return glm::vec3(model * glm::vec4(glm::vec3(d), 0.0F));
}

// Builds every cue of the replica's current state. `model` places the object frame
// in the world (the renderer's model matrix).
void build_cues(const SceneReplica& replica, const glm::mat4& model, float scene_radius_m,
                const CueOptions& options, CueScene& out);

// The screw axes build_cues draws for the live stroke (world frame): one segment per
// hand whose screw turns (none for a pure translation or scodef).
std::vector<std::pair<glm::vec3, glm::vec3>> drawn_screw_axes(const SceneReplica& replica,
                                                              const glm::mat4& model,
                                                              float scene_radius_m);

// The grab point's path under the stroke's motion, t = 0 .. 1 in `samples` steps
// (object frame); empty for scodef.
std::vector<glm::dvec3> stroke_trajectory(const LiveHand& hand, math::WarpMethod method,
                                          int samples);
// The drawn part of the screw axis (object frame): centred on the foot of the
// grab point, `half_length_m` each way; nullopt for a pure translation or scodef.
std::optional<std::pair<glm::dvec3, glm::dvec3>> screw_axis_segment(const LiveHand& hand,
                                                                    math::WarpMethod method,
                                                                    double half_length_m);

template <typename Extent>
void CueMesh::add_ball(glm::vec3 centre, glm::vec4 colour, int rings, int segments, Extent extent) {
  const auto first = static_cast<std::uint32_t>(vertex_count());
  for (int i = 0; i <= rings; ++i) {
    const float theta = 3.14159265F * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 6.28318531F * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                        std::cos(theta));
      const glm::vec3 p = centre + extent(d) * d;
      positions.insert(positions.end(), {p.x, p.y, p.z});
      colours.insert(colours.end(), {colour.r, colour.g, colour.b, colour.a});
    }
  }
  const auto at = [first, segments](int i, int j) {
    return first + static_cast<std::uint32_t>(i * segments + (j % segments));
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      indices.insert(indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      indices.insert(indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

}  // namespace twister::bridge
