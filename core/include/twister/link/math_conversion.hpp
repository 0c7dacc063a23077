// Conversions between the link's wire types (Pose, Screw) and core math's Frame and
// Screw, for the link's users that hold both (the station link, the bridge). The
// link library itself stays independent of math: nothing in it includes this file.
#pragma once

#include "twister/link/link_message.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"

namespace twister::link {

inline Pose to_wire(const math::Frame& f) { return {f.origin, f.u, f.v, f.w}; }

inline Screw to_wire(const math::Screw& s) {
  return {s.axis, s.angle, s.slide, s.mid, s.chord, s.cot_half, s.pure_translation};
}

inline math::Frame to_frame(const Pose& p) { return {p.origin, p.u, p.v, p.w}; }

inline math::Screw to_screw(const Screw& s) {
  math::Screw out;
  out.axis = s.axis;
  out.angle = s.angle;
  out.slide = s.slide;
  out.mid = s.mid;
  out.chord = s.chord;
  out.cot_half = s.cot_half;
  out.pure_translation = s.pure_translation;
  return out;
}

}  // namespace twister::link
