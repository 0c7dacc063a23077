// Decay weights and the two-hand squash rule (docs/math.md §4-§5). Double precision,
// world frame, scene units.
#pragma once

#include <glm/vec3.hpp>

namespace twister::math {

// t = cos^2((pi/2)*distance/radius) when distance < radius, else 0. radius > 0.
double decay(double distance, double radius);

// Where hand `grab` evaluates its decay for point p when the other hand grabbed at
// `other` and |other - grab| < radius (§5): the half space towards `other` is
// stretched by radius/s along grab->other (fixed point grab). With no squash
// (|other - grab| >= radius) or for p behind grab, returns p. Needs grab != other.
glm::dvec3 squash_point(glm::dvec3 grab, glm::dvec3 other, double radius, glm::dvec3 p);

// Decay weight of p for the hand grabbed at `grab`; `other` is the other hand's
// grab point or nullptr for one hand. Squash applied as in §5.
double hand_weight(glm::dvec3 grab, const glm::dvec3* other, double radius, glm::dvec3 p);

}  // namespace twister::math
