#include "cue_geometry.hpp"

#include <glm/geometric.hpp>

#include "symmetry_cues.hpp"
#include "twister/math/decay.hpp"
#include "twister/math/screw.hpp"

namespace twister::bridge {
namespace {

// Sizes as fractions of the model's bounding radius.
constexpr float kGlyphLength = 0.22F;
constexpr float kGlyphTube = 0.012F;
constexpr float kCursorBall = 0.035F;
constexpr float kAxisTube = 0.016F;
constexpr float kAxisHalfLength = 0.9F;
constexpr float kTrajectoryTube = 0.012F;
constexpr float kObjectFrameLength = 0.5F;
constexpr int kTrajectorySamples = 33;
constexpr float kSphereAlpha = 0.16F;

void add_axes(CueMesh& m, glm::vec3 origin, const std::array<glm::vec3, 3>& axes, float length,
              float tube) {
  const std::array<glm::vec4, 3> rgb{glm::vec4(0.95F, 0.15F, 0.12F, 1.0F),
                                     glm::vec4(0.15F, 0.85F, 0.2F, 1.0F),
                                     glm::vec4(0.2F, 0.35F, 1.0F, 1.0F)};
  for (std::size_t k = 0; k < 3; ++k) m.add_tube(origin, origin + length * axes[k], tube, rgb[k]);
}

// The ball of influence of a hand at `c`: along each direction, the farthest point
// the station's weight function still reaches (binary search on hand_weight > 0).
void add_influence(CueMesh& m, const glm::mat4& model, glm::dvec3 c, const glm::dvec3* other,
                   double radius, glm::vec4 colour) {
  const glm::dmat3 to_object = glm::transpose(glm::dmat3(glm::mat3(model)));
  const auto extent = [&](glm::vec3 world_dir) {
    const glm::dvec3 d = to_object * glm::dvec3(world_dir);
    double lo = 0.0;
    double hi = radius;
    for (int i = 0; i < 18; ++i) {
      const double mid = 0.5 * (lo + hi);
      (math::hand_weight(c, other, radius, c + mid * d) > 0.0 ? lo : hi) = mid;
    }
    return static_cast<float>(lo);
  };
  m.add_ball(to_world(model, c), colour, 16, 28, extent);
}

void add_hands(const SceneReplica& r, const glm::mat4& model, float scale,
               const CueOptions& options, CueScene& out) {
  const auto& hands = r.hands();
  const double radius = r.live().active ? r.live().radius_m : r.radius_m();
  for (std::size_t h = 0; h < hands.size(); ++h) {
    const HandView& v = hands[h];
    if (!v.present) continue;
    const glm::vec3 origin = to_world(model, v.pose.origin);
    const glm::vec4 colour(h == 0 ? 0.92F : 0.15F, h == 0 ? 0.14F : 0.85F, 0.12F, 1.0F);
    if (options.glyphs) {
      add_axes(out.lines, origin,
               {turn(model, v.pose.u), turn(model, v.pose.v), turn(model, v.pose.w)},
               kGlyphLength * scale, kGlyphTube * scale);
      out.overlay.add_sphere(origin, kCursorBall * scale, colour);
    }
    const HandView& o = hands[1 - h];
    if (options.spheres && radius > 0.0) {
      const bool squash = o.present && glm::distance(o.pose.origin, v.pose.origin) > 1e-9;
      add_influence(out.translucent, model, v.pose.origin, squash ? &o.pose.origin : nullptr,
                    radius, glm::vec4(glm::vec3(colour), kSphereAlpha));
    }
  }
}

void add_stroke(const SceneReplica& r, const glm::mat4& model, float scale,
                const CueOptions& options, CueScene& out) {
  const LiveState& live = r.live();
  if (!live.active) return;
  if (options.screw_axes) {
    for (const auto& [from, to] : drawn_screw_axes(r, model, scale)) {
      out.lines.add_tube(from, to, kAxisTube * scale, kAxisPink, 12);
    }
  }
  for (std::size_t k = 0; k < live.hands.size(); ++k) {
    const LiveHand& hand = live.hands[k];
    if (options.trajectories) {
      const auto path = stroke_trajectory(hand, live.method, kTrajectorySamples);
      for (std::size_t i = 1; i < path.size(); ++i) {
        out.lines.add_tube(to_world(model, path[i - 1]), to_world(model, path[i]),
                           kTrajectoryTube * scale, kTrajectoryYellow, 8);
      }
    }
  }
}

}  // namespace

void CueMesh::clear() {
  positions.clear();
  colours.clear();
  indices.clear();
}

void CueMesh::add_tube(glm::vec3 a, glm::vec3 b, float radius, glm::vec4 colour, int sides) {
  const glm::vec3 axis = b - a;
  const float len = glm::length(axis);
  if (!(len > 0.0F)) return;
  const glm::vec3 d = axis / len;
  const glm::vec3 e1 =
      glm::normalize(glm::cross(d, std::abs(d.x) < 0.9F ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 e2 = glm::cross(d, e1);
  const auto first = static_cast<std::uint32_t>(vertex_count());
  for (int end = 0; end < 2; ++end) {
    const glm::vec3 c = end == 0 ? a : b;
    for (int j = 0; j < sides; ++j) {
      const float phi = 6.28318531F * static_cast<float>(j) / static_cast<float>(sides);
      const glm::vec3 p = c + radius * (std::cos(phi) * e1 + std::sin(phi) * e2);
      positions.insert(positions.end(), {p.x, p.y, p.z});
      colours.insert(colours.end(), {colour.r, colour.g, colour.b, colour.a});
    }
  }
  const auto s = static_cast<std::uint32_t>(sides);
  for (std::uint32_t j = 0; j < s; ++j) {
    const std::uint32_t j1 = (j + 1) % s;
    indices.insert(indices.end(), {first + j, first + s + j, first + s + j1});
    indices.insert(indices.end(), {first + j, first + s + j1, first + j1});
  }
  for (std::uint32_t j = 1; j + 1 < s; ++j) {  // end caps as fans
    indices.insert(indices.end(), {first, first + j + 1, first + j});
    indices.insert(indices.end(), {first + s, first + s + j, first + s + j + 1});
  }
}

std::vector<glm::dvec3> stroke_trajectory(const LiveHand& hand, math::WarpMethod method,
                                          int samples) {
  std::vector<glm::dvec3> path;
  if (method == math::WarpMethod::scodef || samples < 2) return path;
  const glm::dvec3 grab = hand.start.origin;
  for (int i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(samples - 1);
    path.push_back(method == math::WarpMethod::rottran
                       ? math::rottran_at(hand.screw, hand.start, hand.end, t, grab)
                       : math::screw_at(hand.screw, t, grab));
  }
  return path;
}

std::optional<std::pair<glm::dvec3, glm::dvec3>> screw_axis_segment(const LiveHand& hand,
                                                                    math::WarpMethod method,
                                                                    double half_length_m) {
  if (method == math::WarpMethod::scodef || hand.screw.pure_translation) return std::nullopt;
  // rottran turns about the axis through the grab point; twister about the screw's.
  const glm::dvec3 a =
      method == math::WarpMethod::rottran ? hand.start.origin : hand.screw.axis_point();
  const glm::dvec3 d = hand.screw.axis;
  const glm::dvec3 foot = a + glm::dot(hand.start.origin - a, d) * d;
  return std::make_pair(foot - half_length_m * d, foot + half_length_m * d);
}

std::vector<std::pair<glm::vec3, glm::vec3>> drawn_screw_axes(const SceneReplica& replica,
                                                              const glm::mat4& model,
                                                              float scene_radius_m) {
  std::vector<std::pair<glm::vec3, glm::vec3>> out;
  const LiveState& live = replica.live();
  if (!live.active) return out;
  for (const LiveHand& hand : live.hands) {
    if (const auto axis = screw_axis_segment(hand, live.method, kAxisHalfLength * scene_radius_m)) {
      out.emplace_back(to_world(model, axis->first), to_world(model, axis->second));
    }
  }
  return out;
}

void build_cues(const SceneReplica& replica, const glm::mat4& model, float scene_radius_m,
                const CueOptions& options, CueScene& out) {
  out.lines.clear();
  out.translucent.clear();
  out.overlay.clear();
  add_hands(replica, model, scene_radius_m, options, out);
  add_stroke(replica, model, scene_radius_m, options, out);
  if (options.glyphs) add_symmetry_cues(replica, model, scene_radius_m, out);
  bool moving = false;
  for (const HandView& v : replica.hands()) moving = moving || (v.present && v.move_object);
  if (options.object_frame && moving) {
    const math::Frame& f = replica.object_pose();
    add_axes(out.lines, glm::vec3(f.origin), {glm::vec3(f.u), glm::vec3(f.v), glm::vec3(f.w)},
             kObjectFrameLength * scene_radius_m, 1.5F * kGlyphTube * scene_radius_m);
    out.lines.add_sphere(glm::vec3(f.origin), 2.0F * kGlyphTube * scene_radius_m,
                         glm::vec4(0.9F, 0.9F, 0.9F, 1.0F));
  }
}

}  // namespace twister::bridge
