// SceneReplica: the mesh (full meshes and commits, verified by checksum), the
// object pose and the station status. The live stroke and the hands are in
// live_replica.cpp.
#include "scene_replica.hpp"

#include <algorithm>
#include <utility>

#include "replica_plan.hpp"
#include "twister/link/math_conversion.hpp"
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

SceneReplica::SceneReplica(ReplicaLimits limits) : limits_(limits) {}
SceneReplica::~SceneReplica() = default;
SceneReplica::SceneReplica(SceneReplica&&) noexcept = default;

void SceneReplica::set_crease_angle(float degrees) {
  crease_angle_deg_ = degrees;
  if (!has_mesh()) return;
  shaded_ = shade_with_creases(mesh_, crease_angle_deg_);
  mesh_changed_ = true;  // drawn again with the new shading
}
SceneReplica& SceneReplica::operator=(SceneReplica&&) noexcept = default;

std::optional<link::ResendRequest> SceneReplica::request() {
  ++counters_.resend_requests;
  staging_ = false;
  return link::ResendRequest{version_, checksum_};
}

std::optional<link::ResendRequest> SceneReplica::apply(const link::LinkMessage& m) {
  std::optional<link::ResendRequest> out;
  if (const auto* b = std::get_if<link::MeshBegin>(&m)) {
    begin(*b);
    if (!b->full && !staging_ && b->base_version != version_ &&
        b->vertex_count <= limits_.max_vertices && b->triangle_count <= limits_.max_triangles) {
      ++counters_.version_gaps;  // we missed a commit (link loss): start over
      out = request();
    }
  } else if (const auto* v = std::get_if<link::Vertices>(&m)) {
    on_vertices(*v);
  } else if (const auto* t = std::get_if<link::Triangles>(&m)) {
    on_triangles(*t);
  } else if (const auto* e = std::get_if<link::MeshEnd>(&m)) {
    end(*e, out);
  } else if (const auto* stroke = std::get_if<link::StrokeBegin>(&m)) {
    on_stroke(*stroke);
  } else if (const auto* hands = std::get_if<link::Hands>(&m)) {
    on_hands(*hands);
  } else if (const auto* object = std::get_if<link::ObjectPose>(&m)) {
    object_pose_ = link::from_compact(object->pose);
  } else if (const auto* workspace = std::get_if<link::Workspace>(&m)) {
    workspace_ = *workspace;
    has_workspace_ = true;
  } else if (const auto* status = std::get_if<link::StatusReport>(&m)) {
    status_ = *status;
    has_status_ = true;
  } else if (const auto* visitor = std::get_if<link::VisitorState>(&m)) {
    visitor_ = *visitor;
    has_visitor_ = true;
  } else if (const auto* notice = std::get_if<link::Notice>(&m)) {
    ++notices_received_;
    notices_[(notices_received_ - 1) % notices_.size()] = {*notice, notices_received_};
  }
  // Handshake messages belong to BridgeApp; resend_request to the station.
  return out;
}

std::vector<ReceivedNotice> SceneReplica::notices() const {
  std::vector<ReceivedNotice> out;
  const std::uint64_t kept = std::min<std::uint64_t>(notices_received_, notices_.size());
  for (std::uint64_t n = notices_received_ - kept + 1; n <= notices_received_; ++n)
    out.push_back(notices_[(n - 1) % notices_.size()]);
  return out;
}

void SceneReplica::begin(const link::MeshBegin& b) {
  begin_ = b;
  staging_bad_ = false;
  staging_ = false;
  // Announced counts are checked before anything is allocated.
  if (b.vertex_count > limits_.max_vertices || b.triangle_count > limits_.max_triangles) {
    ++counters_.over_capacity;
    return;
  }
  staging_ = b.full || b.base_version == version_;
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

void SceneReplica::on_vertices(const link::Vertices& v) {
  if (!staging_) return;
  for (std::size_t i = 0; i < v.count; ++i) {
    const link::VertexEntry& e = v.items[i];
    if (e.index >= staged_.vertex_count()) {
      staging_bad_ = true;
      continue;
    }
    staged_.x[e.index] = e.x;
    staged_.y[e.index] = e.y;
    staged_.z[e.index] = e.z;
  }
}

void SceneReplica::on_triangles(const link::Triangles& t) {
  if (!staging_) return;
  if (static_cast<std::size_t>(t.first) + t.count > staged_.triangle_count()) {
    staging_bad_ = true;
    return;
  }
  std::copy_n(t.indices.begin(), std::size_t{3} * t.count,
              staged_.indices.begin() + 3 * static_cast<std::ptrdiff_t>(t.first));
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
  shaded_ = shade_with_creases(mesh_, crease_angle_deg_);
  version_ = e.version;
  checksum_ = *sum;
  mesh_changed_ = true;
  if (begin_.full) {
    ++counters_.full_meshes;
  } else {
    ++counters_.commits;
  }
  // A commit ends the live preview of its stroke; a later segment's weights are
  // built on the new mesh.
  live_.active = false;
  plan_.reset();
}

}  // namespace twister::bridge
