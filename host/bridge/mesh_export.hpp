// Mesh export of the replica, chosen by the file extension: OBJ through hal/meshio
// (the CLI's writer), binary little-endian PLY, or glTF 2.0 through tinygltf
// (`.glb` binary, `.gltf` with the buffer embedded) with vertex normals. Object
// frame, metres. check_export_path() is run at start, so a bad path or format is
// refused before the session's work, not after it.
#pragma once

#include <string>
#include <vector>

#include "scene_replica.hpp"
#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Errors: invalid_argument (unknown extension: names the ones accepted; the path
// is a directory), io_error (the folder does not exist or is not writable),
// failed_precondition (the programs' output rule, twister/hal/output_file.hpp: an
// existing file is replaced only with `force` and only when it is of the same kind,
// never a journal, checkpoint or locked file).
hal::Expected<void> check_export_path(const std::string& path, bool force = false);

// Writes `mesh` to `path`; glTF gets `shaded`'s crease-aware normals (e.g.
// SceneReplica::shading(): a crease's two sides are separate vertices); OBJ and PLY
// carry positions and triangles only. Errors: invalid_argument (unknown extension,
// triangle index out of range, shading of another mesh), io_error (cannot open or
// write); the message names the path.
hal::Expected<void> export_mesh(const std::string& path, const MeshData& mesh,
                                const ShadedMesh& shaded, bool force = false);
// The same with the default crease angle.
hal::Expected<void> export_mesh(const std::string& path, const MeshData& mesh, bool force = false);

}  // namespace twister::bridge
