// SymmetryBuffer: host-side owner of a symmetric WarpPlan's storage (math::PlanSymmetry:
// the chain-start columns, and the float path's ball words and kept weights) for a
// plan of `vertex_capacity` vertices, sized once (the station, `twister replay` and
// `export`, the display's replica). Everyone who warps a symmetric stroke holds the same
// storage, so each computes it as the station did (the float path; without the ball
// words and weights a plan falls back to the double path, docs/math.md §11.7).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "twister/math/symmetric_kernel.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::meshio {

class SymmetryBuffer {
 public:
  explicit SymmetryBuffer(std::size_t vertex_capacity)
      : x_(vertex_capacity),
        y_(vertex_capacity),
        z_(vertex_capacity),
        balls_(math::SymmetricFloat::words_for(vertex_capacity)),
        weights_(math::SymmetricFloat::weights_for(vertex_capacity)),
        symmetry_(std::make_unique<math::PlanSymmetry>()) {
    symmetry_->start = math::VertexColumns{x_, y_, z_};
    symmetry_->balls = balls_;
    symmetry_->weights = weights_;
  }
  SymmetryBuffer(const SymmetryBuffer&) = delete;
  SymmetryBuffer& operator=(const SymmetryBuffer&) = delete;

  // The bytes such a buffer holds (a station's memory budget).
  static std::size_t bytes_for(std::size_t vertex_capacity) {
    return 3 * sizeof(float) * vertex_capacity + sizeof(math::PlanSymmetry) +
           sizeof(std::uint64_t) * math::SymmetricFloat::words_for(vertex_capacity) +
           sizeof(float) * math::SymmetricFloat::weights_for(vertex_capacity);
  }

  // For WarpPlanStorage::symmetry (stays valid as long as the buffer).
  math::PlanSymmetry* plan_symmetry() { return symmetry_.get(); }

 private:
  std::vector<float> x_, y_, z_;
  std::vector<std::uint64_t> balls_;
  std::vector<float> weights_;
  std::unique_ptr<math::PlanSymmetry> symmetry_;  // its address is handed out: heap
};

}  // namespace twister::meshio
