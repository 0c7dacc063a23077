// The station side and the display replica of bench/latency_probe.cpp: a
// SculptSession on a UV sphere of radius 0.5 m (hand 1 grabbing its top with radius
// 1 m: every vertex is influenced), and a bridge::SceneReplica holding the same mesh
// and the stroke, ready for hands messages.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::bench {

class LatencyRig {
 public:
  explicit LatencyRig(std::size_t vertices)
      : rings_(static_cast<std::size_t>(std::sqrt(static_cast<double>(vertices) / 2.0))),
        buffer_(meshio::sphere_vertices(rings_, 2 * rings_),
                meshio::sphere_triangles(rings_, 2 * rings_)) {
    (void)meshio::make_sphere(buffer_.mesh(), rings_, 2 * rings_, 0.5F);
    const std::size_t n = buffer_.mesh().vertex_count();
    for (auto* v : {&lx_, &ly_, &lz_, &w1_, &w2_}) v->resize(n);
    indices_.resize(n);
    changes_.resize(session::kDefaultUndoChanges);
    entries_.resize(session::kDefaultUndoEntries);
    session::SculptSessionConfig config;
    for (auto& i : config.debounce.interval_us) i = 0;
    config.interaction.initial_radius_m = 1.0F;
    session_ = std::make_unique<session::SculptSession>(
        config, buffer_.mesh(),
        session::SculptStorage{lx_, ly_, lz_, math::WarpPlanStorage{indices_, w1_, w2_}, changes_,
                               entries_},
        nullptr);
    start_ = math::frame_from_uv({0.0, 0.0, 0.5}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
    (void)session_->set_hand(1, true, start_);
    (void)session_->feed_button({3, true, now_});
    (void)session_->step(++now_);
    ready_ = session_->live().plan != nullptr && load_replica();
  }

  bool ready() const { return ready_; }
  std::size_t vertices() const { return buffer_.mesh().vertex_count(); }
  bridge::SceneReplica& replica() { return replica_; }

  // The station's work for one pose of hand 1: the session step (the plan follows
  // the hand; no CPU warp of the vertices), then the hands message for the display.
  link::Hands step(const Pose& pose) {
    (void)session_->set_hand(1, true, pose);
    (void)session_->step(++now_);
    return messages(pose).hands;
  }

 private:
  bridge::LiveMessages messages(const math::Frame& end) const {
    const std::array<math::Frame, 2> s{start_, start_};
    const std::array<math::Frame, 2> e{end, end};
    return bridge::make_live_messages(1, 1, math::WarpMethod::twister, 1.0, 2, s, e);
  }

  bool load_replica() {
    const mesh::Mesh& m = buffer_.mesh();
    link::MeshBegin b;
    b = {true, 0, 1, static_cast<std::uint32_t>(m.vertex_count()),
         static_cast<std::uint32_t>(m.triangle_count())};
    if (replica_.apply(b).has_value()) return false;
    link::Vertices v;
    for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
      v.items[v.count++] = {i, m.x()[i], m.y()[i], m.z()[i]};
      if (v.count == link::kMaxVerticesPerChunk || i + 1 == m.vertex_count()) {
        (void)replica_.apply(v);
        v.count = 0;
      }
    }
    const auto idx = m.triangle_indices();
    link::Triangles t;
    for (std::size_t k = 0; k < m.triangle_count(); k += link::kMaxTrianglesPerChunk) {
      const auto n = std::min<std::size_t>(link::kMaxTrianglesPerChunk, m.triangle_count() - k);
      t.first = static_cast<std::uint32_t>(k);
      t.count = static_cast<std::uint16_t>(n);
      std::copy_n(idx.begin() + 3 * static_cast<std::ptrdiff_t>(k), 3 * n, t.indices.begin());
      (void)replica_.apply(t);
    }
    bridge::MeshData d;
    d.x.assign(m.x().begin(), m.x().end());
    d.y.assign(m.y().begin(), m.y().end());
    d.z.assign(m.z().begin(), m.z().end());
    d.indices.assign(idx.begin(), idx.end());
    link::MeshEnd e;
    e = {1, *bridge::mesh_checksum(d)};
    if (replica_.apply(e).has_value()) return false;
    const auto live = messages(start_);
    return !replica_.apply(live.stroke).has_value() && !replica_.apply(live.hands).has_value();
  }

  std::size_t rings_;
  meshio::MeshBuffer buffer_;
  std::vector<float> lx_, ly_, lz_, w1_, w2_;
  std::vector<std::uint32_t> indices_;
  std::vector<session::VertexChange> changes_;
  std::vector<session::UndoEntry> entries_;
  std::unique_ptr<session::SculptSession> session_;
  bridge::SceneReplica replica_;
  math::Frame start_{};
  ports::TimestampUs now_ = 0;
  bool ready_ = false;
};

}  // namespace twister::bench
