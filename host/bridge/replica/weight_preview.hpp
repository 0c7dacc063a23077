// WeightPreview: the weights each present hand would give the mesh if it grabbed
// now (the paper's colour feedback "before" a grab, which helps the sculptor place
// the trackers). They are the station's own weights: a math::WarpPlan built on the
// rest mesh with the hands' current positions and the session's radius (decay and
// the two-hand squash of core math, nothing recomputed here). Rebuilt only when a
// hand moved, the radius changed or the mesh changed. Object frame, metres.
// Columns by session hand: hand1 (red), hand2 (green); 0 = not influenced.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene_replica.hpp"

namespace twister::bridge {

class WeightPreview {
 public:
  // Recomputes the weights when something they depend on changed; returns true
  // when hand1()/hand2() changed. `mesh_version` identifies the mesh.
  bool update(const MeshData& mesh, std::uint32_t mesh_version,
              const std::array<HandView, link::kLinkHands>& hands, double radius_m);
  const std::vector<float>& hand1() const { return w_[0]; }
  const std::vector<float>& hand2() const { return w_[1]; }
  // Hands with a weight column in use (bit h: session hand h).
  std::uint8_t hand_mask() const { return mask_; }
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  void rebuild(const MeshData& mesh, const std::array<glm::dvec3, 2>& at, std::uint8_t mask,
               double radius_m);

  std::array<std::vector<float>, 2> w_;
  std::array<glm::dvec3, 2> at_{};
  std::uint8_t mask_ = 0;
  double radius_m_ = -1.0;
  std::uint32_t version_ = 0;
  std::size_t vertices_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool valid_ = false;
  // Plan storage, sized to the mesh.
  std::vector<std::uint32_t> indices_;
  std::vector<float> p1_, p2_;
};

}  // namespace twister::bridge
