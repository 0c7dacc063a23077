#include "twister/mesh/triangle_adjacency.hpp"

namespace twister::mesh {
namespace {

// Not yet linked (build() only; never a twin value).
constexpr std::uint32_t kUnset = 0xfffffffdu;

bool degenerate(const std::uint32_t* v) { return v[0] == v[1] || v[1] == v[2] || v[2] == v[0]; }

}  // namespace

bool TriangleAdjacency::fits(const Mesh& mesh) const {
  const std::size_t half_edges = 3 * mesh.triangle_capacity();
  return storage_.twins.size() >= half_edges && storage_.incident.size() >= half_edges &&
         storage_.vertex_offsets.size() >= mesh.vertex_capacity() + 1;
}

Status TriangleAdjacency::build(const Mesh& mesh) {
  if (!fits(mesh)) return StatusCode::resource_exhausted;
  const std::size_t n = mesh.vertex_count();
  const auto indices = mesh.triangle_indices();
  std::span<std::uint32_t> offsets = storage_.vertex_offsets.first(n + 1);
  for (std::uint32_t& o : offsets) o = 0;
  for (const std::uint32_t v : indices) ++offsets[v + 1];
  for (std::size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  // Fill with offsets[v] as v's write cursor, then shift the cursors back to starts.
  for (std::size_t k = 0; k < indices.size(); ++k) {
    storage_.incident[offsets[indices[k]]++] = static_cast<std::uint32_t>(k / 3);
  }
  for (std::size_t v = n; v > 0; --v) offsets[v] = offsets[v - 1];
  offsets[0] = 0;
  std::span<std::uint32_t> twins = storage_.twins.first(indices.size());
  for (std::uint32_t& t : twins) t = kUnset;
  // Twins are symmetric: a half-edge found as the twin of an earlier one is done.
  for (std::uint32_t h = 0; h < twins.size(); ++h) {
    if (twins[h] == kUnset) link(h, find_twin(indices, h));
  }
  return ok_status();
}

std::uint32_t TriangleAdjacency::find_twin(std::span<const std::uint32_t> indices,
                                           std::uint32_t h) const {
  const std::uint32_t t = h / 3;
  const std::uint32_t* tv = indices.data() + 3 * std::size_t{t};
  if (degenerate(tv)) return kNonManifold;
  const std::uint32_t a = tv[h % 3];
  const std::uint32_t b = tv[h % 3 == 2 ? 0 : h % 3 + 1];
  std::uint32_t found = kBoundary;
  for (std::uint32_t k = storage_.vertex_offsets[a]; k < storage_.vertex_offsets[a + 1]; ++k) {
    const std::uint32_t u = storage_.incident[k];
    if (u == t) continue;
    const std::uint32_t* uv = indices.data() + 3 * std::size_t{u};
    for (std::uint32_t j = 0; j < 3; ++j) {
      const std::uint32_t p = uv[j];
      const std::uint32_t q = uv[j == 2 ? 0 : j + 1];
      if (!((p == a && q == b) || (p == b && q == a))) continue;
      if (found != kBoundary || degenerate(uv)) return kNonManifold;
      found = 3 * u + j;
    }
  }
  return found;
}

void TriangleAdjacency::link(std::uint32_t h, std::uint32_t g) {
  storage_.twins[h] = g;
  if (g != kBoundary && g != kNonManifold) storage_.twins[g] = h;
}

}  // namespace twister::mesh
