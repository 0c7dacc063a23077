// Mesh export of the replica: OBJ through hal/meshio (same writer as the CLI
// tools) or binary little-endian PLY, chosen by the file extension.
#pragma once

#include <string>

#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Writes `mesh` to `path`. Errors: invalid_argument (unknown extension, triangle
// index out of range), io_error (cannot open or write); the message names the path.
hal::Expected<void> export_mesh(const std::string& path, const MeshData& mesh);

}  // namespace twister::bridge
