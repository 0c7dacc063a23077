// Mesh export of the replica: OBJ through hal/meshio (same writer as the CLI
// tools) or binary little-endian PLY, chosen by the file extension.
#pragma once

#include <string>

#include "scene_replica.hpp"

namespace twister::bridge {

// true on success; otherwise `message` says why (unknown extension, I/O error).
bool export_mesh(const std::string& path, const MeshData& mesh, std::string& message);

}  // namespace twister::bridge
