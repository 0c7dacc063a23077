// The bridge's message handling (issue 11): SceneReplica fed with arbitrary input,
// in three modes chosen by the first byte, so the fuzzer reaches past the CRC:
//   0: raw bytes through the frame decoder (what a peer can send);
//   1: length-prefixed payloads ([n][version, type, body...]) straight to
//      decode_payload, then to the replica;
//   2: as 1, after a valid 4 x 4 grid mesh was received (strokes, hands, commits
//      against a mesh the replica holds).
// Properties: never crashes or allocates what a peer announces beyond the limits
// (the replica's limits are small here: a violation shows as an ASan OOM); a held
// mesh always matches its checksum and stays within the limits; poses of present
// hands are finite; the CPU warp of a live stroke has the mesh's size; a symmetric
// stroke's shader entries stay inside their arrays.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"

namespace {

using namespace twister;

constexpr bridge::ReplicaLimits kLimits{4096, 8192};

void load_grid(bridge::SceneReplica& r) {
  bridge::MeshData m;
  for (std::uint32_t j = 0; j < 4; ++j) {
    for (std::uint32_t i = 0; i < 4; ++i) {
      m.x.push_back(0.1F * static_cast<float>(i));
      m.y.push_back(0.1F * static_cast<float>(j));
      m.z.push_back(0.0F);
    }
  }
  for (std::uint32_t j = 0; j < 3; ++j) {
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t a = 4 * j + i;
      m.indices.insert(m.indices.end(), {a, a + 1, a + 4, a + 1, a + 5, a + 4});
    }
  }
  (void)r.apply(link::MeshBegin{true, 0, 1, 16, 18});
  static link::Vertices vertices;
  vertices.count = 16;
  for (std::uint32_t i = 0; i < 16; ++i) vertices.items[i] = {i, m.x[i], m.y[i], m.z[i]};
  (void)r.apply(vertices);
  static link::Triangles triangles;
  triangles.first = 0;
  triangles.count = 18;
  for (std::size_t i = 0; i < m.indices.size(); ++i) triangles.indices[i] = m.indices[i];
  (void)r.apply(triangles);
  (void)r.apply(link::MeshEnd{1, *bridge::mesh_checksum(m)});
  if (!r.has_mesh()) std::abort();
}

void check(const bridge::SceneReplica& r) {
  if (r.has_mesh()) {
    const auto sum = bridge::mesh_checksum(r.mesh());
    if (!sum || *sum != r.checksum()) std::abort();
    if (r.mesh().vertex_count() > kLimits.max_vertices ||
        r.mesh().triangle_count() > kLimits.max_triangles) {
      std::abort();
    }
  }
  for (const bridge::HandView& h : r.hands()) {
    if (h.present && !(std::isfinite(h.pose.origin.x) && std::isfinite(h.pose.u.y))) std::abort();
  }
  // A symmetric stroke's shader entries (symmetric_live.hpp) stay within their arrays:
  // every vertex's span inside the entries, every entry's image one of the plan's.
  const bridge::SymmetricLive& gpu = r.live().symmetric_gpu;
  if (gpu.ready) {
    if (gpu.spans.size() != 2 * r.mesh().vertex_count() ||
        gpu.entries.size() != 4 * gpu.entry_count()) {
      std::abort();
    }
    for (std::size_t v = 0; 2 * v < gpu.spans.size(); ++v) {
      if (gpu.spans[2 * v] + gpu.spans[2 * v + 1] > static_cast<float>(gpu.entry_count())) {
        std::abort();
      }
    }
    for (std::size_t e = 0; e < gpu.entry_count(); ++e) {
      if (!(gpu.entries[4 * e] > 0.0F && gpu.entries[4 * e] <= 1.0F)) std::abort();
      if (gpu.image_count != 0 && gpu.entry_image[e] >= gpu.image_count) std::abort();
    }
  }
  if (r.live().active) {
    const bridge::MeshData warped = r.cpu_warp();
    if (warped.vertex_count() != 0 && warped.vertex_count() != r.mesh().vertex_count()) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  bridge::SceneReplica replica(kLimits);
  const std::uint8_t mode = data[0] % 3;
  const auto* bytes = reinterpret_cast<const std::byte*>(data + 1);
  const std::size_t n = size - 1;
  if (mode == 0) {
    static link::LinkDecoder decoder;
    decoder.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (const auto m = decoder.process(bytes[i]); m.ok()) {
        (void)replica.apply(**m);
        check(replica);
      }
    }
    return 0;
  }
  if (mode == 2) load_grid(replica);
  static link::LinkMessage message;
  for (std::size_t i = 0; i < n;) {
    const std::size_t len = std::to_integer<std::size_t>(bytes[i]);
    ++i;
    const std::size_t take = len < n - i ? len : n - i;
    if (link::decode_payload(std::span<const std::byte>(bytes + i, take), message).ok()) {
      (void)replica.apply(message);
      check(replica);
    }
    i += take;
  }
  return 0;
}
