#include "twister/session/commit_refinement.hpp"

#include <cmath>
#include <utility>

#include "twister/base/assert.hpp"
#include "twister/session/plan_warp.hpp"

namespace twister::session {
namespace {

// Records each pre-existing triangle in the open undo entry before it changes.
class UndoTriangles final : public mesh::RefineObserver {
 public:
  explicit UndoTriangles(UndoHistory& undo) : undo_(undo) {}
  bool overflow = false;

 private:
  void do_triangle_changing(std::uint32_t t, const std::array<std::uint32_t, 3>& before) override {
    if (!undo_.record_triangle(t, before).ok()) overflow = true;
  }
  UndoHistory& undo_;
};

}  // namespace

CommitRefinement::CommitRefinement(LiveMesh& mesh, mesh::MeshRefinerStorage storage,
                                   const RefineConfig& config, math::VertexColumns chain_start)
    : mesh_(mesh), refiner_(storage), config_(config), chain_(chain_start) {}

double CommitRefinement::threshold_for(const math::WarpPlan& plan,
                                       const journal::StrokeRecord& stroke,
                                       bool plan_goes_on) const {
  if (!config_.enabled || plan_goes_on) return 0.0;
  if (!refiner_.fits(mesh_.mesh()) || !(config_.threshold_m > 0.0)) return 0.0;
  // A chain's end: only with every step composed (ClutchChain).
  if (stroke.chain_step != 0 && !chain_refinable(plan, stroke.chain_step)) return 0.0;
  return config_.threshold_m;
}

void CommitRefinement::chain_ended_unrefined() {
  if (chain_.too_long()) ++totals_.chains_too_long;
}

double CommitRefinement::live_threshold() const {
  if (!config_.enabled || !refiner_.fits(mesh_.mesh()) || !(config_.threshold_m > 0.0)) return 0.0;
  return config_.threshold_m;
}

RefineReport CommitRefinement::refine(const math::WarpPlan& plan, double threshold_m,
                                      UndoHistory& undo, bool local) {
  // The plan's vertices are already warped into the live columns by the kernel the
  // float filter would use: the filter takes them instead of warping them again.
  const math::ConstVertexColumns live = std::as_const(mesh_).live();
  return refine_with(PlanWarp(plan), plan.indices(), threshold_m, undo, local,
                     {live.x, live.y, live.z});
}

RefineReport CommitRefinement::refine_chain(const math::WarpPlan& plan, double threshold_m,
                                            UndoHistory& undo, bool local) {
  if (!(threshold_m > 0.0) || !std::isfinite(threshold_m)) return {};
  // The refiner works on rest positions: the chain's start, where C is defined. Only
  // the plan's vertices moved during the chain (freeze steps change no topology).
  chain_.restore_start(plan, mesh_.mesh());
  RefineReport report =
      refine_with(ChainWarp(chain_), plan.indices(), threshold_m, undo, local, {});
  ++totals_.refined_chains;
  return report;
}

RefineReport CommitRefinement::refine_with(const mesh::PointWarp& warp,
                                           std::span<const std::uint32_t> region,
                                           double threshold_m, UndoHistory& undo, bool local,
                                           mesh::VertexImages images) {
  RefineReport report;
  if (!(threshold_m > 0.0) || !std::isfinite(threshold_m)) return report;
  mesh::Mesh& m = mesh_.mesh();
  const auto vertices = static_cast<std::uint32_t>(m.vertex_count());
  const auto triangles = static_cast<std::uint32_t>(m.triangle_count());
  UndoTriangles observer(undo);
  const Result<mesh::RefineResult> refined =
      local ? refiner_.refine_around(m, warp, threshold_m, region, &observer, images)
            : refiner_.refine(m, warp, threshold_m, &observer);
  TWISTER_ASSERT(refined.ok());  // available() and a valid threshold
  report.result = *refined;
  report.ran = true;
  report.undoable = !observer.overflow;
  // The new vertices are no plan vertex: from their rest midpoint to S of it.
  for (std::uint32_t v = vertices; v < m.vertex_count(); ++v) {
    const glm::vec3 placed(refiner_.warped(v));
    if (!undo.record(v, m.position(v), placed).ok()) report.undoable = false;
    m.set_position(v, placed);
  }
  if (!undo.record_topology(m, vertices, triangles).ok()) report.undoable = false;
  ++totals_.refined_commits;
  totals_.vertices_added += report.result.edges_split;
  totals_.last_stop = report.result.stop;
  if (report.result.stop != mesh::RefineStop::done) ++totals_.capacity_stops;
  totals_.last_vertices_added = report.result.edges_split;
  totals_.last_blocked = report.result.blocked;
  return report;
}

RefineStatus CommitRefinement::status() const {
  RefineStatus s = totals_;
  const mesh::Mesh& m = mesh_.mesh();
  s.enabled = config_.enabled;
  s.available = refiner_.fits(m);
  s.threshold_m = config_.threshold_m;
  s.spare_vertices = m.vertex_capacity() - m.vertex_count();
  s.spare_triangles = m.triangle_capacity() - m.triangle_count();
  return s;
}

}  // namespace twister::session
