// ClutchChain: what refining a clutch chain at its end needs (docs/refinement.md
// "Clutch chains"). A chain's freeze steps keep the step-0 plan's vertex set and its
// weights (WarpPlan::rebase); step j's commit moves each of the plan's vertices from
// where the previous step left it, q_j, to
//   q_{j+1} = q_j + sum_h (S_jh(w_h(p), q_j) - q_j)
// with S_jh hand h's screw (or rottran) of step j at weight t and w_h(p) the step-0
// weight of the vertex's chain-start (rest) position p. So the whole chain is the
// point function C(p) = step k o ... o step 0 (p), every step weighted by w_h(p); C is
// what ChainWarp evaluates for the refiner, in double.
//
// note() sees every commit before it changes the mesh: step 0 starts a chain (kept
// when asked: the chain-start positions of the plan's vertices copied from the mesh,
// the step-0 grabs and radius that define w_h), each later step adds its screws and
// poses. Bounded: at most kMaxChainSteps steps; a longer chain is kept no further
// (too_long()) and its end is committed unrefined. scodef chains are not kept (its
// displacement has no weight a later step could reuse; not refined), nor are symmetric
// ones (docs/math.md §11: C would need every image's steps; committed unrefined).
// Memory: the chain-start columns are the caller's (one float per plan vertex of
// capacity, each column); no allocation. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>

#include "twister/base/inline_vector.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/vertex_columns.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/mesh/point_warp.hpp"

namespace twister::session {

// Steps of one chain a refinement can compose (a 360-degree twist in 120-degree clutch
// steps is 3; 16 is far beyond what a hand does in one stroke).
inline constexpr std::size_t kMaxChainSteps = 16;

// One committed step: each plan hand's screw (long turns included) and poses.
struct ChainStep {
  std::array<math::Screw, math::kMaxHands> screws{};
  std::array<math::Frame, math::kMaxHands> start{};  // rottran turns about the start
  std::array<math::Frame, math::kMaxHands> end{};
};

class ClutchChain {
 public:
  // `start_storage`: chain-start positions, each column at least the plan's capacity
  // (empty: chains are never kept, so never refined).
  explicit ClutchChain(math::VertexColumns start_storage);
  ClutchChain(const ClutchChain&) = delete;
  ClutchChain& operator=(const ClutchChain&) = delete;

  // A commit of `plan` (updated to its end poses) as chain step `step` is about to
  // change `mesh`. Step 0 begins a chain, kept when `keep` (and the storage holds
  // the plan, and it is not scodef); a later step continues the kept chain when it is
  // its next step with the same plan shape on the same topology, else drops it.
  void note(const math::WarpPlan& plan, std::uint16_t step, bool keep, const mesh::Mesh& mesh);
  // A commit of `plan` as step `step` (> 0) can end the chain refined: its steps
  // 0..step-1 are kept and there is room for this one (asked before note()).
  bool refinable(const math::WarpPlan& plan, std::uint16_t step, const mesh::Mesh& mesh) const;
  // The chain was kept but grew past kMaxChainSteps.
  bool too_long() const { return overflow_; }
  // Puts the chain-start positions of the plan's vertices back into `mesh` (after
  // note() of the chain's last step).
  void restore_start(const math::WarpPlan& plan, mesh::Mesh& mesh) const;
  // C(p): the chain's steps so far applied to the chain-start point p.
  glm::dvec3 warp_point(glm::dvec3 p) const;
  // Drops the chain (an undo, a redo, a restored checkpoint).
  void forget() { kept_ = false; }
  std::size_t steps() const { return steps_.size(); }

 private:
  bool continues(const math::WarpPlan& plan, std::uint16_t step, const mesh::Mesh& mesh) const;

  math::VertexColumns start_;
  std::size_t hands_ = 0;
  double radius_ = 0.0;
  math::WarpMethod method_ = math::WarpMethod::twister;
  std::array<glm::dvec3, math::kMaxHands> grabs_{};  // step 0's grab points: w_h
  InlineVector<ChainStep, kMaxChainSteps> steps_;
  std::uint32_t next_step_ = 0;  // the chain step note() expects next
  bool kept_ = false;
  bool overflow_ = false;
  // The plan's vertex count and the mesh's shape when the chain began: freeze steps
  // change positions only.
  std::size_t plan_vertices_ = 0;
  std::size_t mesh_vertices_ = 0;
  std::uint64_t topology_ = 0;
};

// The refiner's warp of a chain's end: C of ClutchChain, double precision, no float
// batch (the refiner then settles every edge in double). Holds a reference.
class ChainWarp final : public mesh::PointWarp {
 public:
  explicit ChainWarp(const ClutchChain& chain) : chain_(chain) {}

 private:
  glm::dvec3 do_warp(glm::dvec3 rest_m) const override { return chain_.warp_point(rest_m); }
  const ClutchChain& chain_;
};

}  // namespace twister::session
