// Conversions between the link's compact wire poses and core math's Frame and Screw
// (the exact pose needs none: math::Frame is twister::Pose, the link's own), for
// the link's users that hold both (the station link, the bridge). The link library
// itself stays independent of math: nothing in it includes this file.
//
// Live warp (docs/link-protocol.md): the station sends, per hand in the open
// stroke, the end position (floats) and the rotation from the start frame to the
// end frame as a *signed* unit quaternion: (cos(a/2), sin(a/2) D) of the station's
// screw (angle a, axis D). The bridge rebuilds the end frame from the exact start
// frame and that rotation, and the screw with live_screw(): the minimal screw of
// the two frames, taken the other way round when it disagrees with the sent sense.
// So the bridge turns the way the station turned, also at and past a half turn,
// whatever the rounding of the floats.
#pragma once

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <numbers>

#include "twister/link/link_message.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"

namespace twister::link {

// The frame's orientation (columns U, V, W) as a unit quaternion.
inline glm::dquat frame_rotation(const math::Frame& f) {
  return glm::normalize(glm::quat_cast(glm::dmat3(f.u, f.v, f.w)));
}

inline glm::dquat wire_rotation(const CompactPose& p) {
  const glm::dquat q(p.rotation[0], p.rotation[1], p.rotation[2], p.rotation[3]);
  return glm::normalize(q);
}

inline CompactPose compact(glm::dvec3 position, const glm::dquat& q) {
  CompactPose p;
  p.position = glm::vec3(position);
  p.rotation = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                static_cast<float>(q.z)};
  return p;
}

// A hand (or the object) as a compact pose: w >= 0.
inline CompactPose to_compact(const math::Frame& f) {
  glm::dquat q = frame_rotation(f);
  if (q.w < 0.0) q = -q;
  return compact(f.origin, q);
}

// The frame whose axes are the columns of `q`'s rotation, at `origin`.
inline math::Frame frame_of(glm::dvec3 origin, const glm::dquat& q) {
  const glm::dmat3 r = glm::mat3_cast(q);
  return math::Frame{origin, r[0], r[1], r[2]};
}

inline math::Frame from_compact(const CompactPose& p) {
  return frame_of(glm::dvec3(p.position), wire_rotation(p));
}

// The signed rotation start -> end of `screw` (see above).
inline glm::dquat live_rotation(const math::Frame& start, const math::Frame& end,
                                const math::Screw& screw) {
  glm::dquat q = glm::normalize(glm::quat_cast(
      glm::dmat3(end.u, end.v, end.w) * glm::transpose(glm::dmat3(start.u, start.v, start.w))));
  if (q.w < 0.0) q = -q;
  if (!screw.pure_translation && glm::dot(glm::dvec3(q.x, q.y, q.z), screw.axis) < 0.0) q = -q;
  return q;
}

// Station side: a stroke hand's sample (end position, signed relative rotation).
inline CompactPose to_live_compact(const math::Frame& start, const math::Frame& end,
                                   const math::Screw& screw) {
  return compact(end.origin, live_rotation(start, end, screw));
}

// Bridge side: the end frame of a stroke hand from its exact start frame.
inline math::Frame live_end_frame(const math::Frame& start, const CompactPose& sample) {
  const glm::dquat r = wire_rotation(sample);
  return frame_of(glm::dvec3(sample.position), r * frame_rotation(start));
}

// The same rotation and end pose taken the other way round: axis -D, angle
// 2 pi - a, slide -d, cot(a/2) negated; the axis point, M and X are unchanged
// (the shape of math's long_way_round). A pure translation is returned unchanged.
inline math::Screw other_way_round(const math::Screw& s) {
  if (s.pure_translation) return s;
  math::Screw out = s;
  out.axis = -s.axis;
  out.angle = 2.0 * std::numbers::pi - s.angle;
  out.slide = -s.slide;
  out.cot_half = -s.cot_half;
  return out;
}

// Bridge side: the station's screw from the frames and the sent rotation's sense.
inline math::Screw live_screw(const math::Frame& start, const math::Frame& end,
                              const CompactPose& sample) {
  const glm::dquat r = wire_rotation(sample);
  const glm::dvec3 sense(r.x, r.y, r.z);
  math::Screw s = math::compute_screw(start, end, sense);  // the hint decides at a half turn
  if (!s.pure_translation && glm::dot(s.axis, sense) < 0.0) s = other_way_round(s);
  return s;
}

}  // namespace twister::link
