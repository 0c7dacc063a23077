#include "weight_preview.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <memory>

#include "twister/base/inline_vector.hpp"
#include "twister/math/warp_plan.hpp"

namespace twister::bridge {
namespace {

// Hands closer than this to where they were keep the previous weights: a
// tracker's jitter (well under a millimetre) does not rebuild a 100k-vertex plan.
constexpr double kMoveThresholdM = 2e-4;

}  // namespace

bool WeightPreview::update(const MeshData& mesh, std::uint32_t mesh_version,
                           const std::array<HandView, link::kLinkHands>& hands, double radius_m) {
  std::array<glm::dvec3, 2> at{};
  std::uint8_t mask = 0;
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if (!hands[h].present) continue;
    at[h] = hands[h].pose.origin;
    mask = static_cast<std::uint8_t>(mask | (1u << h));
  }
  bool same = valid_ && mask == mask_ && radius_m == radius_m_ && version_ == mesh_version &&
              vertices_ == mesh.vertex_count();
  for (std::size_t h = 0; same && h < link::kLinkHands; ++h) {
    if ((mask & (1u << h)) != 0) same = glm::distance(at[h], at_[h]) < kMoveThresholdM;
  }
  if (same) return false;
  rebuild(mesh, at, mask, radius_m);
  version_ = mesh_version;
  vertices_ = mesh.vertex_count();
  valid_ = true;
  ++rebuilds_;
  return true;
}

void WeightPreview::rebuild(const MeshData& mesh, const std::array<glm::dvec3, 2>& at,
                            std::uint8_t mask, double radius_m) {
  at_ = at;
  mask_ = mask;
  radius_m_ = radius_m;
  const std::size_t n = mesh.vertex_count();
  for (auto& w : w_) w.assign(n, 0.0F);
  if (mask == 0 || !(radius_m > 0.0) || n == 0) return;
  indices_.resize(n);
  p1_.resize(n);
  p2_.resize(n);
  auto plan = std::make_unique<math::WarpPlan>(math::WarpPlanStorage{indices_, p1_, p2_});
  const math::ConstVertexColumns rest{mesh.x, mesh.y, mesh.z};
  math::PlanFrames start;  // weights depend on the grab point only
  InlineVector<std::size_t, math::kMaxHands> session;
  static_assert(link::kLinkHands == math::kMaxHands);  // one entry per hand: fits
  for (std::size_t h = 0; h < link::kLinkHands; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    session.push_back(h).ignore();
    start.push_back(math::identity_frame(at[h])).ignore();
  }
  const auto copy_out = [this, &plan, &session](std::size_t first) {
    const auto idx = plan->indices();
    for (std::size_t k = 0; k < plan->hand_count(); ++k) {
      const auto w = plan->weights(k);
      std::vector<float>& column = w_[session[first + k]];
      for (std::size_t i = 0; i < idx.size(); ++i) column[idx[i]] = w[i];
    }
  };
  const Status both = plan->build(rest, start, radius_m, math::WarpMethod::twister);
  if (both.ok()) {
    copy_out(0);
    return;
  }
  if (start.size() < 2) return;
  // Both hands at one point: the squash is undefined (the station refuses such a
  // grab too); show each hand's own ball.
  for (std::size_t k = 0; k < start.size(); ++k) {
    if (plan->build(rest, start.span().subspan(k, 1), radius_m, math::WarpMethod::twister).ok()) {
      copy_out(k);
    }
  }
}

}  // namespace twister::bridge
