#include "twister/session/clutch_chain.hpp"

#include "twister/base/assert.hpp"
#include "twister/math/decay.hpp"

namespace twister::session {

ClutchChain::ClutchChain(math::VertexColumns start_storage) : start_(start_storage) {}

bool ClutchChain::continues(const math::WarpPlan& plan, std::uint16_t step,
                            const mesh::Mesh& mesh) const {
  return kept_ && step == next_step_ && plan.built() && plan.hand_count() == hands_ &&
         plan.radius() == radius_ && plan.method() == method_ &&
         plan.indices().size() == plan_vertices_ && mesh.vertex_count() == mesh_vertices_ &&
         mesh.topology_version() == topology_;
}

void ClutchChain::note(const math::WarpPlan& plan, std::uint16_t step, bool keep,
                       const mesh::Mesh& mesh) {
  if (step == 0) {
    kept_ = false;
    overflow_ = false;
    steps_.clear();
    const std::span<const std::uint32_t> indices = plan.indices();
    // Symmetric chains are not composed (ChainWarp has no images): committed unrefined.
    if (!keep || !plan.built() || plan.method() == math::WarpMethod::scodef || plan.symmetric() ||
        !start_.consistent() || start_.size() < indices.size()) {
      return;
    }
    // The chain-start (rest) positions: the mesh before this commit.
    for (std::size_t i = 0; i < indices.size(); ++i) {
      const glm::vec3 p = mesh.position(indices[i]);
      start_.x[i] = p.x;
      start_.y[i] = p.y;
      start_.z[i] = p.z;
    }
    hands_ = plan.hand_count();
    radius_ = plan.radius();
    method_ = plan.method();
    for (std::size_t h = 0; h < hands_; ++h) grabs_[h] = plan.start_frame(h).origin;
    plan_vertices_ = indices.size();
    mesh_vertices_ = mesh.vertex_count();
    topology_ = mesh.topology_version();
    next_step_ = 0;
    kept_ = true;
  } else if (!continues(plan, step, mesh)) {
    kept_ = false;
    return;
  }
  ++next_step_;
  if (overflow_) return;  // counted on, composed no further
  ChainStep s;
  for (std::size_t h = 0; h < hands_; ++h) {
    s.screws[h] = plan.screw(h);
    s.start[h] = plan.start_frame(h);
    s.end[h] = plan.end_frame(h);
  }
  if (!steps_.push_back(s).ok()) overflow_ = true;
}

bool ClutchChain::refinable(const math::WarpPlan& plan, std::uint16_t step,
                            const mesh::Mesh& mesh) const {
  return step > 0 && !overflow_ && steps_.size() < kMaxChainSteps && continues(plan, step, mesh);
}

void ClutchChain::restore_start(const math::WarpPlan& plan, mesh::Mesh& mesh) const {
  const std::span<const std::uint32_t> indices = plan.indices();
  TWISTER_ASSERT(kept_ && indices.size() == plan_vertices_);
  for (std::size_t i = 0; i < indices.size(); ++i) {
    mesh.set_position(indices[i], {start_.x[i], start_.y[i], start_.z[i]});
  }
}

// Step j moves q by the sum of its hands' displacements at q (the kernels' two-hand
// sum), each at the weight of the chain-start point p: what the freeze steps' kernels
// do with the step-0 weights they keep. A hand of weight 0 does not move q (as
// WarpPlan::warp_point).
glm::dvec3 ClutchChain::warp_point(glm::dvec3 p) const {
  std::array<double, math::kMaxHands> w{};
  for (std::size_t h = 0; h < hands_; ++h) {
    const glm::dvec3* other = hands_ == 2 ? &grabs_[1 - h] : nullptr;
    w[h] = math::hand_weight(grabs_[h], other, radius_, p);
  }
  glm::dvec3 q = p;
  for (const ChainStep& s : steps_) {
    glm::dvec3 moved = q;
    for (std::size_t h = 0; h < hands_; ++h) {
      if (w[h] <= 0.0) continue;
      const glm::dvec3 r = method_ == math::WarpMethod::rottran
                               ? math::rottran_at(s.screws[h], s.start[h], s.end[h], w[h], q)
                               : math::screw_at(s.screws[h], w[h], q);
      moved += r - q;
    }
    q = moved;
  }
  return q;
}

}  // namespace twister::session
