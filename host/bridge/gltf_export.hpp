// glTF 2.0 export (tinygltf): one mesh, one primitive of triangles with POSITION
// and NORMAL (float) and uint32 indices, one node, one scene. Private to the
// bridge library (mesh_export.cpp chooses it by extension).
#pragma once

#include <string>
#include <vector>

#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

// The file's bytes: `binary` .glb, otherwise .gltf with the buffer embedded as a
// data URI. `shaded`: the mesh's crease-aware shading (its drawn vertices become
// the file's vertices). Error io_error when tinygltf cannot write.
hal::Expected<std::string> gltf_bytes(const MeshData& mesh, const ShadedMesh& shaded, bool binary);

}  // namespace twister::bridge
