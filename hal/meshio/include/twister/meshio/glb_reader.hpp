// Reads the triangles of a binary glTF (.glb) through tinygltf (Debian's
// libtinygltf-dev, a reader we did not write): the positions and indices of every
// triangle primitive of every mesh, node transforms not applied (the station's and
// the display's .glb have one node without one: +Y up, metres, centred; docs/exhibit.md
// "Exports"). Bounded: the file's size is checked before tinygltf reads it whole, and
// the counts before anything is copied. Host side (the display's attract showcase).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>

#include "twister/hal/expected.hpp"
#include "twister/meshio/mesh_buffer.hpp"

namespace twister::meshio {

struct GlbReadLimits {
  std::size_t max_file_bytes = std::size_t{64} << 20;
  std::size_t max_vertices = 1'000'000;
  std::size_t max_triangles = 2'000'000;
};

// io_error: cannot be read; invalid_argument: not a .glb tinygltf accepts, or its
// triangles are malformed (an accessor out of its buffer, an index past the
// vertices, a non-finite position, no triangles); resource_exhausted: larger than
// the limits. The message names the file and the problem.
hal::Expected<std::unique_ptr<MeshBuffer>> read_glb(const std::string& path,
                                                    const GlbReadLimits& limits = {});
// The same over a file's bytes; `name` names it in the messages (the fuzz target).
hal::Expected<std::unique_ptr<MeshBuffer>> parse_glb(std::span<const unsigned char> bytes,
                                                     const std::string& name,
                                                     const GlbReadLimits& limits = {});

}  // namespace twister::meshio
