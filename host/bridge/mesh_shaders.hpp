// GLSL of MeshRenderer (private to the bridge library). The displacement is core's
// scalar kernel term by term (warp_kernels_scalar.cpp), so the preview equals the
// CPU warp up to float rounding. Two programs share the warp library below:
//  - plain (GLSL 3.30): the mesh's own vertices, warped in the vertex shader with
//    the stroke's weights (attribute); the warped normal comes from the same warp
//    taken at two nearby points along the rest surface (weights moved along their
//    gradients): the surface's tangent plane after the warp;
//  - refined (GLSL 4.00, tessellation; the live stroke on a GL 4 context): each
//    triangle is a patch whose edges are cut into n equal parts, n = ceil(sqrt(2e/τ))
//    with e the edge's midpoint error |(S(A)+S(B))/2 - S((A+B)/2)| under the current
//    warp (the worst of its whole, halves and quarters, scaled) and τ the threshold
//    the commit refines to (a part's error falls as 1/n²: each part aims at τ/2):
//    the paper's criterion, evaluated per frame; the inside at least as finely,
//    more where the centroid's error says so. New points sit on the flat
//    rest triangle, as the commit's new vertices do, and are warped with weights
//    computed here from the rest position (core's decay and squash, decay.cpp), so
//    no attribute is interpolated. A shared edge gets the same n from both patches
//    (the error is symmetric in A and B) and the same points (snapped to k/n and
//    taken from the edge's lexicographically first end): no cracks.
// A third program warps a stroke under a symmetry group (kSymmetricVertex).
// All write the object-frame rest and warped positions for transform feedback
// (MeshRenderer::capture_live_surface).
#pragma once

namespace twister::bridge::shaders {

// Uniforms and functions of the warp (no #version: prepended per program).
inline constexpr const char* kWarpLibrary = R"(
uniform int u_hand_mask;
uniform vec3 u_axis[2];
uniform vec3 u_mid[2];
uniform vec3 u_chord[2];
uniform vec3 u_axc[2];
uniform vec3 u_shift[2];
uniform float u_half[2];
uniform float u_cot[2];
uniform vec3 u_grab[2];
uniform float u_radius;
vec3 displacement(int h, vec3 p, float t) {
  vec3 d = u_axis[h];
  vec3 v = p - u_mid[h];
  float hl = t * u_half[h];
  float sh = sin(hl);
  float ch = cos(hl);
  float a = sh * ch;
  float b = sh * sh;
  float k = u_cot[h];
  float dv = dot(d, v);
  vec3 c = cross(d, v);
  return a * (2.0 * c + k * u_chord[h]) + b * (2.0 * (d * dv - v) + k * u_axc[h]) +
         t * u_shift[h];
}
vec3 warp(vec3 p, vec2 w) {
  vec3 q = p;
  if ((u_hand_mask & 1) != 0 && w.x > 0.0) q += displacement(0, p, w.x);
  if ((u_hand_mask & 2) != 0 && w.y > 0.0) q += displacement(1, p, w.y);
  return q;
}
float decay(float d, float r) {
  if (!(d < r)) return 0.0;
  float c = cos(1.5707963267948966 * d / r);
  return c * c;
}
// The other grab point's squash of hand g's ball (decay.cpp squash_point).
vec3 squash(vec3 g, vec3 o, float r, vec3 p) {
  vec3 oq = o - g;
  float s = length(oq);
  if (!(s < r) || s <= 0.0) return p;
  float proj = dot(p - g, oq);
  if (proj < 0.0) return p;
  return p + (proj / s) * ((r - s) / s) * (oq / s);
}
vec2 weights_at(vec3 p) {
  bool two = (u_hand_mask & 2) != 0;
  vec3 p0 = two ? squash(u_grab[0], u_grab[1], u_radius, p) : p;
  float w0 = decay(length(p0 - u_grab[0]), u_radius);
  float w1 = two ? decay(length(squash(u_grab[1], u_grab[0], u_radius, p) - u_grab[1]), u_radius)
                 : 0.0;
  return vec2(w0, w1);
}
vec3 warp_at(vec3 p) { return warp(p, weights_at(p)); }
// An edge's ends in a fixed order, so both of its patches use the same operands.
bool before(vec3 a, vec3 b) {
  return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}
)";

// The last vertex stage of both programs (after the warp library): the outputs the
// fragment shader and transform feedback read, and the warped normal's frame.
inline constexpr const char* kSurfaceStage = R"(
uniform mat4 u_view_proj;
uniform mat4 u_model;
uniform float u_eps;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_weight;
out vec3 v_rest;
out vec3 v_object;
// Two unit tangents of the rest surface with normal n (t1 x t2 = n).
void tangents(vec3 n, out vec3 t1, out vec3 t2) {
  t1 = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  t2 = cross(n, t1);
}
// Rest point p, warped to q with weights w and normal n (object frame).
void emit(vec3 p, vec3 q, vec3 n, vec2 w) {
  vec4 world = u_model * vec4(q, 1.0);
  v_pos = world.xyz;
  v_normal = mat3(u_model) * n;
  v_weight = w;
  v_rest = p;
  v_object = q;
  gl_Position = u_view_proj * world;
}
)";

inline constexpr const char* kPlainVertex = R"(
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec2 a_weight;
layout(location = 2) in vec3 a_normal;
layout(location = 3) in vec3 a_grad0;
layout(location = 4) in vec3 a_grad1;
void main() {
  vec3 p = a_pos;
  vec3 q = warp(p, a_weight);
  vec3 n = a_normal;
  if (u_hand_mask != 0 && (a_weight.x > 0.0 || a_weight.y > 0.0)) {
    vec3 t1, t2;
    tangents(n, t1, t2);
    vec3 q1 = warp(p + u_eps * t1, a_weight + u_eps * vec2(dot(a_grad0, t1), dot(a_grad1, t1)));
    vec3 q2 = warp(p + u_eps * t2, a_weight + u_eps * vec2(dot(a_grad0, t2), dot(a_grad1, t2)));
    vec3 m = cross(q1 - q, q2 - q);
    if (dot(m, m) > 0.0) n = normalize(m);
  }
  emit(p, q, n, a_weight);
}
)";

// Symmetric program (GLSL 3.30; docs/math.md §11.2, §11.7): a stroke under a symmetry
// group. Per vertex its entries (a_span: first, count) in two texture buffers: the
// weight and its gradient (u_entries), the image (u_entry_image); per image its kernel
// constants in a uniform block (symmetric_live.hpp SymmetricImageGpu: g S_h g^-1, the
// axis turned over by a reflection, and the share 1/|G_h|). The vertex moves by the sum
// of share * displacement(image, p, weight) over its entries, as the float path sums
// it; the normal as the plain program's, every entry's weight moved along its gradient.
inline constexpr const char* kSymmetricVertex = R"(
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec2 a_weight;
layout(location = 2) in vec3 a_normal;
layout(location = 5) in vec2 a_span;
uniform samplerBuffer u_entries;
uniform usamplerBuffer u_entry_image;
layout(std140) uniform Images {
  vec4 u_image[5 * 48];
};
vec3 image_displacement(int i, vec3 p, float t) {
  if (!(t > 0.0)) return vec3(0.0);
  vec4 axis_half = u_image[5 * i];
  vec4 mid_cot = u_image[5 * i + 1];
  vec4 chord_share = u_image[5 * i + 2];
  vec3 d = axis_half.xyz;
  vec3 v = p - mid_cot.xyz;
  float hl = t * axis_half.w;
  float sh = sin(hl);
  float ch = cos(hl);
  float a = sh * ch;
  float b = sh * sh;
  float k = mid_cot.w;
  float dv = dot(d, v);
  vec3 c = cross(d, v);
  return chord_share.w * (a * (2.0 * c + k * chord_share.xyz) +
                          b * (2.0 * (d * dv - v) + k * u_image[5 * i + 3].xyz) +
                          t * u_image[5 * i + 4].xyz);
}
void main() {
  vec3 p = a_pos;
  vec3 q = p;
  vec3 n = a_normal;
  int first = int(a_span.x);
  int count = int(a_span.y);
  if (count > 0) {
    vec3 t1, t2;
    tangents(n, t1, t2);
    vec3 p1 = p + u_eps * t1;
    vec3 p2 = p + u_eps * t2;
    vec3 q1 = p1;
    vec3 q2 = p2;
    for (int e = first; e < first + count; ++e) {
      vec4 wg = texelFetch(u_entries, e);
      int i = int(texelFetch(u_entry_image, e).r);
      q += image_displacement(i, p, wg.x);
      q1 += image_displacement(i, p1, wg.x + u_eps * dot(wg.yzw, t1));
      q2 += image_displacement(i, p2, wg.x + u_eps * dot(wg.yzw, t2));
    }
    vec3 m = cross(q1 - q, q2 - q);
    if (dot(m, m) > 0.0) n = normalize(m);
  }
  emit(p, q, n, a_weight);
}
)";

// Refined program: the vertex stage only hands the rest vertex on.
inline constexpr const char* kRefinedVertex = R"(
layout(location = 0) in vec3 a_pos;
layout(location = 2) in vec3 a_normal;
out vec3 c_pos;
out vec3 c_normal;
void main() {
  c_pos = a_pos;
  c_normal = a_normal;
}
)";

inline constexpr const char* kRefinedControl = R"(
layout(vertices = 3) out;
in vec3 c_pos[];
in vec3 c_normal[];
out vec3 e_pos[];
out vec3 e_normal[];
uniform float u_threshold;
uniform float u_max_level;
// The paper's criterion on the edge, on its halves and on its quarters: cutting a
// piece into n parts divides its midpoint error by about n² where the curvature is
// even, so the worst of e, 4 e_half and 16 e_quarter is the whole edge's error
// where it bends most (a warp bends unevenly along a long coarse edge). Parts aim
// at half the threshold. The edge is walked from its lexicographically first end,
// so both of its patches compute the same level from the same operands.
float err(vec3 a, vec3 m, vec3 b) {
  precise vec3 chord = 0.5 * (a + b);
  precise float e = length(chord - m);
  return e;
}
const float kShortEdge = 0.25;
float level_for(float error) {
  return clamp(ceil(sqrt(2.0 * error / u_threshold)), 1.0, u_max_level);
}
// w[i]: the warp at i/8 along the edge from its first end (w[0], w[8] its ends).
// An edge short against the radius bends evenly along its length: its midpoint
// alone tells (a dense mesh pays one warp per edge, not seven).
float edge_error(vec3 a, vec3 b, vec3 wa, vec3 wb, out vec3 mid) {
  bool forward = before(a, b);
  vec3 lo = forward ? a : b;
  vec3 hi = forward ? b : a;
  vec3 w[9];
  w[0] = forward ? wa : wb;
  w[8] = forward ? wb : wa;
  w[4] = warp_at(0.5 * (lo + hi));
  mid = w[4];
  float e = err(w[0], w[4], w[8]);
  if (length(hi - lo) < kShortEdge * u_radius) return e;
  for (int i = 1; i < 8; ++i) {
    if (i != 4) w[i] = warp_at(mix(lo, hi, float(i) / 8.0));
  }
  e = max(e, 4.0 * max(err(w[0], w[2], w[4]), err(w[4], w[6], w[8])));
  for (int i = 0; i < 8; i += 2) e = max(e, 16.0 * err(w[i], w[i + 1], w[i + 2]));
  return e;
}
void main() {
  e_pos[gl_InvocationID] = c_pos[gl_InvocationID];
  e_normal[gl_InvocationID] = c_normal[gl_InvocationID];
  if (gl_InvocationID != 0) return;
  vec3 a = c_pos[0];
  vec3 b = c_pos[1];
  vec3 c = c_pos[2];
  vec3 wa = warp_at(a);
  vec3 wb = warp_at(b);
  vec3 wc = warp_at(c);
  vec3 mbc, mca, mab;
  // Outer level i is the edge opposite corner i.
  float l0 = level_for(edge_error(b, c, wb, wc, mbc));
  float l1 = level_for(edge_error(c, a, wc, wa, mca));
  float l2 = level_for(edge_error(a, b, wa, wb, mab));
  // Inside: the centroid's error, and four times that of the four half-size
  // triangles' centroids (their corners' warps known from the edges).
  vec3 ab = 0.5 * (a + b);
  vec3 bc = 0.5 * (b + c);
  vec3 ca = 0.5 * (c + a);
  float e = length((wa + wb + wc) / 3.0 - warp_at((a + b + c) / 3.0));
  float longest = max(length(b - a), max(length(c - b), length(a - c)));
  if (longest >= kShortEdge * u_radius) {
    e = max(e, 4.0 * length((wa + mab + mca) / 3.0 - warp_at((a + ab + ca) / 3.0)));
    e = max(e, 4.0 * length((mab + wb + mbc) / 3.0 - warp_at((ab + b + bc) / 3.0)));
    e = max(e, 4.0 * length((mca + mbc + wc) / 3.0 - warp_at((ca + bc + c) / 3.0)));
    e = max(e, 4.0 * length((mab + mbc + mca) / 3.0 - warp_at((ab + bc + ca) / 3.0)));
  }
  gl_TessLevelOuter[0] = l0;
  gl_TessLevelOuter[1] = l1;
  gl_TessLevelOuter[2] = l2;
  gl_TessLevelInner[0] = max(level_for(e), max(l0, max(l1, l2)));
}
)";

inline constexpr const char* kRefinedEvaluation = R"(
layout(triangles, equal_spacing, ccw) in;
in vec3 e_pos[];
in vec3 e_normal[];
// A point of the edge (a, b) cut into n parts, the same from both of its patches:
// k/n from the edge's first end.
vec3 on_edge(vec3 a, float ta, vec3 b, float n) {
  vec3 lo = before(a, b) ? a : b;
  vec3 hi = before(a, b) ? b : a;
  float k = round((before(a, b) ? 1.0 - ta : ta) * n);
  return mix(lo, hi, k / n);
}
void main() {
  vec3 t = gl_TessCoord;
  precise vec3 p;
  if (t.x == 0.0) {
    p = on_edge(e_pos[1], t.y, e_pos[2], gl_TessLevelOuter[0]);
  } else if (t.y == 0.0) {
    p = on_edge(e_pos[2], t.z, e_pos[0], gl_TessLevelOuter[1]);
  } else if (t.z == 0.0) {
    p = on_edge(e_pos[0], t.x, e_pos[1], gl_TessLevelOuter[2]);
  } else {
    p = t.x * e_pos[0] + t.y * e_pos[1] + t.z * e_pos[2];
  }
  vec3 n = t.x * e_normal[0] + t.y * e_normal[1] + t.z * e_normal[2];
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  vec2 w = weights_at(p);
  vec3 q = warp(p, w);
  if (w.x > 0.0 || w.y > 0.0) {
    vec3 t1, t2;
    tangents(n, t1, t2);
    vec3 m = cross(warp_at(p + u_eps * t1) - q, warp_at(p + u_eps * t2) - q);
    if (dot(m, m) > 0.0) n = normalize(m);
  }
  emit(p, q, n, w);
}
)";

// Two-sided lighting (a key light, a fill from below-behind, a rim term and a
// specular highlight) so the shape reads; weights tint towards each hand's colour
// (hand 1 red, hand 2 green, blended where both reach).
inline constexpr const char* kMeshFragment = R"(
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_weight;
uniform vec3 u_eye;
uniform vec3 u_light0;
uniform vec3 u_light1;
uniform int u_show_weights;
uniform vec3 u_tint[2];
out vec4 frag;
void main() {
  vec3 n = normalize(v_normal);
  vec3 to_eye = normalize(u_eye - v_pos);
  if (dot(n, to_eye) < 0.0) n = -n;
  vec3 base = vec3(0.78, 0.80, 0.86);
  float s = clamp(v_weight.x, 0.0, 1.0) + clamp(v_weight.y, 0.0, 1.0);
  if (u_show_weights != 0 && s > 0.0) {
    vec3 tint = (clamp(v_weight.x, 0.0, 1.0) * u_tint[0] + clamp(v_weight.y, 0.0, 1.0) * u_tint[1]) / s;
    base = mix(base, tint, 0.85 * clamp(s, 0.0, 1.0));
  }
  float d0 = max(dot(n, u_light0), 0.0);
  float d1 = max(dot(n, u_light1), 0.0);
  float rim = pow(1.0 - max(dot(n, to_eye), 0.0), 3.0);
  vec3 h = normalize(u_light0 + to_eye);
  float spec = pow(max(dot(n, h), 0.0), 48.0);
  vec3 c = base * (0.18 + 0.72 * d0 + 0.22 * d1 + 0.20 * rim) + vec3(0.28) * spec;
  frag = vec4(pow(c, vec3(1.0 / 1.1)), 1.0);
}
)";

}  // namespace twister::bridge::shaders
