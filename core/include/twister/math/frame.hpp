// Frame: a hand pose (origin and orthonormal axes), double precision, in world
// coordinates (metres or any consistent scene unit). W is always U x V.
#pragma once

#include <glm/vec3.hpp>

#include "twister/base/pose.hpp"

namespace twister::math {

// Tolerance of the orthonormality check (docs/math.md §10: unit and orthogonal within 1e-6).
inline constexpr double kFrameTolerance = 1e-6;

// The project's one pose type (twister/base/pose.hpp) under the name the math uses.
using Frame = twister::Pose;

// The world-aligned frame at `origin`.
Frame identity_frame(glm::dvec3 origin = glm::dvec3(0.0));

// A frame from origin, U and V with W = U x V (no check; see is_orthonormal).
Frame frame_from_uv(glm::dvec3 origin, glm::dvec3 u, glm::dvec3 v);

// True when |U|, |V|, |W| are 1 and the pairwise dot products 0 within `tolerance`,
// W equals U x V within `tolerance`, and every component is finite.
bool is_orthonormal(const Frame& frame, double tolerance = kFrameTolerance);

}  // namespace twister::math
