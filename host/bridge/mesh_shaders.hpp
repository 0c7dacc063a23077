// GLSL of MeshRenderer (private to the bridge library). The displacement is core's
// scalar kernel term by term (warp_kernels_scalar.cpp), so the preview equals the
// CPU warp up to float rounding. The warped normal comes from the same warp taken
// at two nearby points along the rest surface (with the weights moved along their
// gradients): the surface's tangent plane after the warp, so smooth shading
// follows the warp with no normal recomputation on the CPU.
#pragma once

namespace twister::bridge::shaders {

inline constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec2 a_weight;
layout(location = 2) in vec3 a_normal;
layout(location = 3) in vec3 a_grad0;
layout(location = 4) in vec3 a_grad1;
uniform mat4 u_view_proj;
uniform mat4 u_model;
uniform int u_hand_mask;
uniform float u_eps;
uniform vec3 u_axis[2];
uniform vec3 u_mid[2];
uniform vec3 u_chord[2];
uniform vec3 u_axc[2];
uniform vec3 u_shift[2];
uniform float u_half[2];
uniform float u_cot[2];
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_weight;
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
void main() {
  vec3 p = a_pos;
  vec3 q = warp(p, a_weight);
  vec3 n = a_normal;
  if (u_hand_mask != 0 && (a_weight.x > 0.0 || a_weight.y > 0.0)) {
    vec3 t1 = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 t2 = cross(n, t1);
    vec3 q1 = warp(p + u_eps * t1, a_weight + u_eps * vec2(dot(a_grad0, t1), dot(a_grad1, t1)));
    vec3 q2 = warp(p + u_eps * t2, a_weight + u_eps * vec2(dot(a_grad0, t2), dot(a_grad1, t2)));
    vec3 m = cross(q1 - q, q2 - q);
    if (dot(m, m) > 0.0) n = normalize(m);
  }
  vec4 world = u_model * vec4(q, 1.0);
  v_pos = world.xyz;
  v_normal = mat3(u_model) * n;
  v_weight = a_weight;
  gl_Position = u_view_proj * world;
}
)";

// Two-sided lighting (a key light, a fill from below-behind, a rim term and a
// specular highlight) so the shape reads; weights tint towards each hand's colour
// (hand 1 red, hand 2 green, blended where both reach).
inline constexpr const char* kMeshFragment = R"(#version 330 core
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
