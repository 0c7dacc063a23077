// PointWarp: a space warp evaluated one point at a time in double precision, for
// work that needs the warp between vertices (adaptive refinement evaluates it at
// edge midpoints). Positions are rest positions in the mesh's frame (metres); the
// result is where the warp takes that point. Implementations must be deterministic
// (the same point gives the same bits) and must not allocate.
#pragma once

#include <glm/vec3.hpp>

namespace twister::mesh {

class PointWarp {
 public:
  virtual ~PointWarp() = default;

  glm::dvec3 warp(glm::dvec3 rest_m) const { return do_warp(rest_m); }

 private:
  virtual glm::dvec3 do_warp(glm::dvec3 rest_m) const = 0;
};

}  // namespace twister::mesh
