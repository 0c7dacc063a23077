// The caller storage a StationLink takes, for tests: the shadow mesh columns and the
// bulk buffer sized from the mesh's capacity, and with spectator slots their queues
// (16 frames each) and the commit staging buffer (16 frames).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "twister/link/link_codec.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/station/station_link.hpp"

namespace twister::test {

struct StationLinkBuffers {
  void size_for(const mesh::Mesh& mesh, std::size_t spectator_slots = 0) {
    x.resize(mesh.vertex_capacity());
    y.resize(mesh.vertex_capacity());
    z.resize(mesh.vertex_capacity());
    idx.resize(3 * mesh.triangle_capacity());
    out.resize(64 * link::kMaxFrameBytes);
    if (spectator_slots == 0) return;
    queues.resize(spectator_slots * 16 * link::kMaxFrameBytes);
    staging.resize(16 * link::kMaxFrameBytes);
  }
  station::StationLinkStorage storage() { return {x, y, z, idx, out}; }

  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out, queues, staging;
};

}  // namespace twister::test
