// Fuzz target of the OBJ loader (hal/meshio's strict reader). Properties: never
// crashes; a loaded mesh has only finite positions and in-range indices, and exactly
// the capacity its counts need; saving and loading it again gives a bit-identical mesh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "twister/meshio/obj_file.hpp"

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1 << 16)) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto loaded = twister::meshio::parse_obj(text);
  if (!loaded) {
    check(!loaded.error().message.empty());
    return 0;
  }
  const twister::mesh::Mesh& m = loaded->buffer->mesh();
  check(m.vertex_capacity() == m.vertex_count());
  check(m.triangle_capacity() == m.triangle_count());
  check(m.vertex_count() > 0);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    check(std::isfinite(m.x()[i]) && std::isfinite(m.y()[i]) && std::isfinite(m.z()[i]));
  }
  for (const std::uint32_t index : m.triangle_indices()) check(index < m.vertex_count());
  const auto again = twister::meshio::parse_obj(twister::meshio::obj_text(m));
  check(again.has_value());
  check(again->buffer->mesh().checksum() == m.checksum());
  return 0;
}
