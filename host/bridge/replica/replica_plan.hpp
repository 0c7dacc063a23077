// The replica's copy of the station's warp plan for the open stroke segment
// (private to the replica library).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "scene_replica.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/meshio/symmetry_buffer.hpp"

namespace twister::bridge {

struct SceneReplica::Plan {
  std::vector<std::uint32_t> indices;
  std::vector<float> w1, w2;
  // Symmetric strokes (docs/math.md §11): the plan's symmetric storage, as the
  // station holds it (so the preview is computed as the commit is).
  std::unique_ptr<meshio::SymmetryBuffer> symmetry;
  std::unique_ptr<math::WarpPlan> plan;
  std::uint32_t stroke = 0;  // the segment it was built for
};

}  // namespace twister::bridge
