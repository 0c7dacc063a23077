// Mesh export of the replica, chosen by the file extension: OBJ through hal/meshio
// (the CLI's writer) and binary little-endian PLY in the object frame, metres, as
// the station holds the model (for replay comparisons); and the visitor's formats
// through hal/meshio's writers (mesh_export.hpp): glTF 2.0 (`.glb` binary, `.gltf`
// with the buffer embedded; metres, +Y up, a pbrMetallicRoughness material, the
// display's crease-aware normals) and binary STL (millimetres, +Z up), both upright
// from `up` (the model's up: the station's workspace up, link `workspace`) and
// centred on the origin. check_export_path() is run at start, so a bad path or
// format is refused before the session's work, not after it.
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Errors: invalid_argument (unknown extension: names the ones accepted (.obj .ply
// .glb .gltf .stl); the path
// is a directory), io_error (the folder does not exist or is not writable),
// failed_precondition (the programs' output rule, twister/hal/output_file.hpp: an
// existing file is replaced only with `force` and only when it is of the same kind,
// never a journal, checkpoint or locked file).
hal::Expected<void> check_export_path(const std::string& path, bool force = false);

// The up of an uncalibrated station's model frame (the transmitter's: +Z down), the
// display's default.
inline constexpr glm::vec3 kTransmitterUp{0.0F, 0.0F, -1.0F};

// Writes `mesh` to `path`; glTF gets `shaded`'s crease-aware normals (e.g.
// SceneReplica::shading(): a crease's two sides are separate vertices); OBJ, PLY and
// STL carry positions and triangles only. Errors: invalid_argument (unknown
// extension, triangle index out of range, shading of another mesh), io_error (cannot
// open or write); the message names the path.
hal::Expected<void> export_mesh(const std::string& path, const MeshData& mesh,
                                const ShadedMesh& shaded, bool force = false,
                                glm::vec3 up = kTransmitterUp);
// The same with the default crease angle.
hal::Expected<void> export_mesh(const std::string& path, const MeshData& mesh, bool force = false,
                                glm::vec3 up = kTransmitterUp);

}  // namespace twister::bridge
