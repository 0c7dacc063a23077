#include "scene_replica.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <numbers>

#include "twister/link/math_conversion.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::bridge {

std::unique_ptr<meshio::MeshBuffer> to_core_mesh(const MeshData& m) {
  auto buffer = std::make_unique<meshio::MeshBuffer>(m.vertex_count(), m.triangle_count());
  mesh::Mesh& mesh = buffer->mesh();
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    if (!mesh.add_vertex({m.x[i], m.y[i], m.z[i]}).ok()) return nullptr;
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    if (!mesh.add_triangle(m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]).ok()) {
      return nullptr;
    }
  }
  return buffer;
}

std::optional<std::uint64_t> mesh_checksum(const MeshData& m) {
  // The station's own checksum code, so "equal" means bit-identical.
  const auto core = to_core_mesh(m);
  if (!core) return std::nullopt;
  return core->mesh().checksum();
}

link::Hello SceneReplica::hello() const {
  return link::Hello{link::Role::bridge, version_, checksum_};
}

std::optional<link::ResendRequest> SceneReplica::request() {
  ++counters_.resend_requests;
  staging_ = false;
  return link::ResendRequest{version_, checksum_};
}

std::optional<link::ResendRequest> SceneReplica::apply(const link::LinkMessage& m) {
  std::optional<link::ResendRequest> out;
  switch (m.type) {
    case link::MessageType::mesh_begin:
      begin(m.mesh_begin);
      if (!m.mesh_begin.full && m.mesh_begin.base_version != version_) {
        ++counters_.version_gaps;  // we missed a commit (link loss): start over
        out = request();
      }
      break;
    case link::MessageType::vertices:
      if (!staging_) break;
      for (std::size_t i = 0; i < m.vertices.count; ++i) {
        const link::VertexEntry& v = m.vertices.items[i];
        if (v.index >= staged_.vertex_count()) {
          staging_bad_ = true;
          continue;
        }
        staged_.x[v.index] = v.x;
        staged_.y[v.index] = v.y;
        staged_.z[v.index] = v.z;
      }
      break;
    case link::MessageType::triangles:
      if (!staging_) break;
      if (static_cast<std::size_t>(m.triangles.first) + m.triangles.count >
          staged_.triangle_count()) {
        staging_bad_ = true;
        break;
      }
      std::copy_n(m.triangles.indices.begin(), std::size_t{3} * m.triangles.count,
                  staged_.indices.begin() + 3 * static_cast<std::ptrdiff_t>(m.triangles.first));
      break;
    case link::MessageType::mesh_end:
      end(m.mesh_end, out);
      break;
    case link::MessageType::live_warp:
      on_live(m.live_warp);
      break;
    case link::MessageType::status:
      status_ = m.status;
      break;
    case link::MessageType::hello:
      // The station's version: our own hello on connect already asked for what we lack.
      break;
    case link::MessageType::resend_request:
      break;  // station side only
  }
  return out;
}

void SceneReplica::begin(const link::MeshBegin& b) {
  begin_ = b;
  staging_ = b.full || b.base_version == version_;
  staging_bad_ = false;
  if (!staging_) return;
  // A commit starts from the current mesh; a full mesh from nothing.
  if (b.full) {
    staged_ = MeshData{};
  } else {
    staged_ = mesh_;
  }
  staged_.x.resize(b.vertex_count, 0.0F);
  staged_.y.resize(b.vertex_count, 0.0F);
  staged_.z.resize(b.vertex_count, 0.0F);
  staged_.indices.resize(3 * static_cast<std::size_t>(b.triangle_count), 0);
}

void SceneReplica::end(const link::MeshEnd& e, std::optional<link::ResendRequest>& out) {
  if (!staging_) return;
  staging_ = false;
  const auto sum = mesh_checksum(staged_);
  if (staging_bad_ || e.version != begin_.version || !sum || *sum != e.checksum) {
    if (staging_bad_) ++counters_.malformed;
    ++counters_.checksum_mismatches;
    out = request();
    return;
  }
  mesh_ = std::move(staged_);
  staged_ = MeshData{};
  version_ = e.version;
  checksum_ = *sum;
  mesh_changed_ = true;
  if (begin_.full) {
    ++counters_.full_meshes;
  } else {
    ++counters_.commits;
  }
  live_.active = false;  // a commit ends the live preview of its stroke
}

void SceneReplica::on_live(const link::LiveWarp& l) {
  ++counters_.live_frames;
  if (!l.active) {
    live_.active = false;
    return;
  }
  if (l.mesh_version != version_ || !has_mesh()) {
    ++counters_.live_stale;
    live_.active = false;
    return;
  }
  const bool new_stroke = !live_.active || l.stroke != live_.stroke ||
                          l.hand_mask != live_.hand_mask || l.radius_m != live_.message.radius_m ||
                          l.method != live_.message.method;
  live_.message = l;
  live_.stroke = l.stroke;
  live_.hand_mask = l.hand_mask;
  live_.method = static_cast<math::WarpMethod>(l.method);
  live_.active = true;
  if (new_stroke) rebuild_weights();
}

namespace {

struct PlanHolder {
  std::vector<std::uint32_t> indices;
  std::vector<float> w1, w2;
  std::unique_ptr<math::WarpPlan> plan;
};

std::unique_ptr<PlanHolder> build_plan(const MeshData& mesh, const link::LiveWarp& l,
                                       bool with_end) {
  auto h = std::make_unique<PlanHolder>();
  const std::size_t n = mesh.vertex_count();
  h->indices.resize(n);
  h->w1.resize(n);
  h->w2.resize(n);
  h->plan = std::make_unique<math::WarpPlan>(math::WarpPlanStorage{h->indices, h->w1, h->w2});
  std::array<math::Frame, 2> start{};
  std::array<math::Frame, 2> end{};
  std::size_t hands = 0;
  std::uint8_t long_turns = 0;
  for (std::size_t k = 0; k < link::kLinkHands; ++k) {
    if ((l.hand_mask & (1u << k)) == 0) continue;
    start[hands] = link::to_frame(l.hands[k].start);
    end[hands] = link::to_frame(l.hands[k].end);
    // The station's screw turns past a half turn (docs/unwrap.md): the same screw the
    // long way round, which the poses alone cannot tell.
    if (l.hands[k].screw.angle > std::numbers::pi) {
      long_turns = static_cast<std::uint8_t>(long_turns | (1u << hands));
    }
    ++hands;
  }
  const math::ConstVertexColumns rest{mesh.x, mesh.y, mesh.z};
  if (!h->plan
           ->build(rest, std::span<const math::Frame>(start.data(), hands), l.radius_m,
                   static_cast<math::WarpMethod>(l.method))
           .ok()) {
    return nullptr;
  }
  if (with_end &&
      !h->plan->update_turns(std::span<const math::Frame>(end.data(), hands), long_turns).ok()) {
    return nullptr;
  }
  return h;
}

}  // namespace

void SceneReplica::rebuild_weights() {
  const std::size_t n = mesh_.vertex_count();
  live_.weight1.assign(n, 0.0F);
  live_.weight2.assign(n, 0.0F);
  live_.weights_changed = true;
  const auto holder = build_plan(mesh_, live_.message, false);
  if (!holder) {
    ++counters_.plan_errors;
    return;
  }
  const auto idx = holder->plan->indices();
  const auto w1 = holder->plan->weights(0);
  const auto w2 = holder->plan->weights(1);
  for (std::size_t k = 0; k < idx.size(); ++k) {
    live_.weight1[idx[k]] = w1[k];
    if (!w2.empty()) live_.weight2[idx[k]] = w2[k];
  }
}

MeshData SceneReplica::cpu_warp() const {
  if (!live_.active) return {};
  const auto holder = build_plan(mesh_, live_.message, true);
  if (!holder) return {};
  MeshData out = mesh_;
  const math::ConstVertexColumns rest{mesh_.x, mesh_.y, mesh_.z};
  (void)holder->plan->apply(rest, math::VertexColumns{out.x, out.y, out.z});
  return out;
}

}  // namespace twister::bridge
