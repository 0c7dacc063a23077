// Wavefront OBJ load (tinyobjloader; positions and faces, polygons triangulated)
// and save (positions as %.9g, so a float survives the round trip exactly, and
// 1-based triangle indices). Units are whatever the file uses (metres for the
// station); no frame conversion.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "twister/base/status.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_buffer.hpp"

namespace twister::meshio {

struct ObjLoad {
  Status status;                       // ok, io_error, invalid_argument
  std::string message;                 // what went wrong (with tinyobjloader's text)
  std::unique_ptr<MeshBuffer> buffer;  // capacity = counts in the file (+ spare)
};

// Parses OBJ text. invalid_argument: no vertices, a face index out of range, a
// non-finite coordinate, a parse error, or more than 2^32-1 vertices.
// spare_vertices / spare_triangles extra capacity for later refinement.
ObjLoad parse_obj(std::string_view text, std::size_t spare_vertices = 0,
                  std::size_t spare_triangles = 0);
// Reads and parses a file; io_error: it cannot be read.
ObjLoad load_obj(const std::filesystem::path& path, std::size_t spare_vertices = 0,
                 std::size_t spare_triangles = 0);

// The OBJ text of a mesh ("v x y z" lines then "f a b c" lines).
std::string obj_text(const mesh::Mesh& mesh);
// Writes obj_text to `path` (via a temporary file and rename, so a crash never
// leaves half a file). io_error with message on failure.
Status save_obj(const std::filesystem::path& path, const mesh::Mesh& mesh, std::string& message);

}  // namespace twister::meshio
