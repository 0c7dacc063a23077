// Fuzz target of hal/meshio's .glb reader (tinygltf underneath; the display's attract
// showcase reads the station's archived models with it). Properties: never crashes;
// a refusal has a message; a mesh read has finite positions, in-range indices and at
// least one triangle, within the limits.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "twister/meshio/glb_reader.hpp"

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  twister::meshio::GlbReadLimits limits;
  limits.max_file_bytes = std::size_t{1} << 20;
  limits.max_vertices = 100'000;
  limits.max_triangles = 100'000;
  const auto read =
      twister::meshio::parse_glb(std::span<const unsigned char>(data, size), "fuzz.glb", limits);
  if (!read) {
    check(!read.error().message.empty());
    return 0;
  }
  const twister::mesh::Mesh& m = (*read)->mesh();
  check(m.triangle_count() > 0 && m.triangle_count() <= limits.max_triangles);
  check(m.vertex_count() <= limits.max_vertices);
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    const auto p = m.position(i);
    check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    for (const std::uint32_t v : m.triangle(t)) check(v < m.vertex_count());
  }
  return 0;
}
