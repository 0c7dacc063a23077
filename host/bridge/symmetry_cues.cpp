#include "symmetry_cues.hpp"

#include <glm/geometric.hpp>

namespace twister::bridge {
namespace {

// Sizes as fractions of the model's bounding radius (cue_geometry.cpp's cursor 0.035).
constexpr float kGhostBall = 0.026F;
constexpr float kGhostGlyphLength = 0.14F;
constexpr float kGhostGlyphTube = 0.006F;
constexpr float kPlaneHalfSize = 1.1F;
constexpr float kAxisHalfLength = 1.3F;
constexpr float kAxisTube = 0.008F;
constexpr glm::vec4 kPlaneColour{0.75F, 0.85F, 1.0F, 0.07F};
constexpr glm::vec4 kAxisColour{0.75F, 0.85F, 1.0F, 1.0F};
constexpr glm::vec4 kGhostAxisTint{0.85F, 0.85F, 0.85F, 1.0F};

// A square of half size `h` in the plane through `c` with in-plane directions a, b.
void add_square(CueMesh& m, glm::vec3 c, glm::vec3 a, glm::vec3 b, float h, glm::vec4 colour) {
  const auto first = static_cast<std::uint32_t>(m.vertex_count());
  for (const glm::vec3 p :
       {c - h * a - h * b, c + h * a - h * b, c + h * a + h * b, c - h * a + h * b}) {
    m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
    m.colours.insert(m.colours.end(), {colour.r, colour.g, colour.b, colour.a});
  }
  // Both windings: the translucent pass culls back faces.
  m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
  m.indices.insert(m.indices.end(), {first, first + 2, first + 1, first, first + 3, first + 2});
}

glm::dvec3 unit(int axis) {
  glm::dvec3 e(0.0);
  e[axis] = 1.0;
  return e;
}

void add_planes_and_axis(const math::SymmetrySpec& spec, const glm::mat4& model, float scale,
                         CueScene& out) {
  const glm::vec3 origin = to_world(model, glm::dvec3(0.0));
  if (spec.kind == math::SymmetryKind::mirrors) {
    for (int a = 0; a < 3; ++a) {
      if ((spec.mirrors & (1u << a)) == 0) continue;
      add_square(out.translucent, origin, turn(model, unit((a + 1) % 3)),
                 turn(model, unit((a + 2) % 3)), kPlaneHalfSize * scale, kPlaneColour);
    }
    return;
  }
  const glm::vec3 axis = turn(model, unit(spec.axis % 3));
  out.lines.add_tube(origin - kAxisHalfLength * scale * axis,
                     origin + kAxisHalfLength * scale * axis, kAxisTube * scale, kAxisColour, 8);
  if (spec.kind != math::SymmetryKind::rotation_mirror) return;
  // Cnv: the n mirror planes through the axis (each contains the axis and one
  // direction at k pi / n from the first perpendicular).
  const glm::dvec3 e1 = unit((spec.axis + 1) % 3);
  const glm::dvec3 e2 = unit((spec.axis + 2) % 3);
  for (int k = 0; k < spec.order; ++k) {
    const double t = 3.141592653589793 * k / spec.order;
    const glm::dvec3 d = std::cos(t) * e1 + std::sin(t) * e2;
    add_square(out.translucent, origin, axis, turn(model, d), kPlaneHalfSize * scale, kPlaneColour);
  }
}

}  // namespace

math::SymmetrySpec shown_symmetry(const SceneReplica& replica) {
  if (replica.live().active) return replica.live().symmetry;
  if (!replica.has_status()) return {};
  const auto& b = replica.station_status().symmetry;
  const math::SymmetrySpec spec{static_cast<math::SymmetryKind>(b[0]), b[1], b[2], b[3]};
  return math::valid_symmetry(spec) ? spec : math::SymmetrySpec{};
}

std::vector<GhostCursor> ghost_cursors(const SceneReplica& replica,
                                       const math::SymmetrySpec& spec) {
  std::vector<GhostCursor> out;
  math::SymmetryGroup group;
  if (!group.set(spec).ok()) return out;
  for (std::size_t h = 0; h < replica.hands().size(); ++h) {
    const HandView& v = replica.hands()[h];
    if (!v.present) continue;
    for (std::size_t i = 1; i < group.order(); ++i) {
      const glm::dvec3 p = group.element(i) * v.pose.origin;
      if (glm::distance(p, v.pose.origin) < 1e-9) continue;  // on a plane or the axis
      out.push_back({h, p, group.element(i)});
    }
  }
  return out;
}

void add_symmetry_cues(const SceneReplica& replica, const glm::mat4& model, float scene_radius_m,
                       CueScene& out) {
  const math::SymmetrySpec spec = shown_symmetry(replica);
  if (spec.kind == math::SymmetryKind::none) return;
  add_planes_and_axis(spec, model, scene_radius_m, out);
  for (const GhostCursor& g : ghost_cursors(replica, spec)) {
    const HandView& v = replica.hands()[g.hand];
    const glm::vec3 at = to_world(model, g.position);
    const glm::vec4 colour = g.hand == 0 ? kGhostHand0 : kGhostHand1;
    for (const glm::dvec3& axis : {v.pose.u, v.pose.v, v.pose.w}) {
      out.lines.add_tube(at,
                         at + kGhostGlyphLength * scene_radius_m * turn(model, g.element * axis),
                         kGhostGlyphTube * scene_radius_m, kGhostAxisTint, 6);
    }
    out.overlay.add_sphere(at, kGhostBall * scene_radius_m, colour);
  }
}

std::string symmetry_name(const math::SymmetrySpec& spec) {
  char label[math::kSymmetryLabelSize] = {};
  return {label, math::symmetry_label(spec, label)};
}

std::string symmetry_hud_line(const SceneReplica& replica) {
  // Nothing on a station without symmetry: a change to "none" shows as a notice.
  const math::SymmetrySpec spec = shown_symmetry(replica);
  if (spec.kind == math::SymmetryKind::none) return {};
  return "symmetry: " + symmetry_name(spec) +
         (replica.live().active ? " (this stroke)" : " (next strokes)");
}

}  // namespace twister::bridge
