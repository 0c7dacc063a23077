// Wavefront OBJ load and save. Units are whatever the file uses (metres for the
// station); no frame conversion.
//
// Loading is strict, streaming and bounded: a file is read in passes through a
// fixed 64 KiB buffer (never held whole in memory), and the mesh is allocated once,
// at exactly the counts the first pass found (plus the requested spare), so memory is
// the mesh's alone. Statements (leading blanks allowed, '#' starts a comment):
//   v x y z [w]  or  v x y z r g b [w-less colour]: 3, 4, 6 or 7 finite numbers
//   vt, vn, vp:  finite numbers (only counted, for face references)
//   f a b c ...: 3 to max_polygon references v, v/vt, v//vn or v/vt/vn, each a
//                non-zero whole number within 32 bits that names an existing element
//                (negative = relative to the elements defined so far)
//   o g s usemtl mtllib: ignored;  l, p, curves and other statements: skipped and
//   counted (ObjMesh::skipped_lines).
// Anything else is an error naming the line: a number with trailing characters, a
// non-finite or out-of-range number, an index of 0 or beyond 32 bits, a reference to
// a missing element, a line longer than 64 KiB. A polygon of more than three vertices
// is triangulated as a fan when it is planar and convex (checked on the positions);
// any other polygon is refused ("triangulate it in the modeller"), never dropped.
// Saving writes "v x y z" (%.9g: every float survives the round trip) and 1-based
// "f a b c" lines through hal::PosixFileSink: a temporary file made durable and
// renamed into place.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include "twister/hal/expected.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_buffer.hpp"

namespace twister::meshio {

struct ObjOptions {
  std::size_t spare_vertices = 0;  // extra capacity (later refinement)
  std::size_t spare_triangles = 0;
  std::size_t max_vertices = std::size_t{1} << 27;  // refuse larger files (memory bound)
  std::size_t max_triangles = std::size_t{1} << 28;
  std::size_t max_polygon = 1024;  // most vertices in one face
};

struct ObjMesh {
  std::unique_ptr<MeshBuffer> buffer;  // capacity = counts in the file + spare
  std::size_t skipped_lines = 0;       // unsupported statements (l, p, curves, ...)
  std::size_t polygons = 0;            // faces of 4+ vertices, triangulated
};

// Parses OBJ text. invalid_argument: the first problem, "line N: ...";
// resource_exhausted: more than the options allow.
hal::Expected<ObjMesh> parse_obj(std::string_view text, const ObjOptions& options = {});
// Reads and parses a file. io_error: it cannot be read (or is not a regular file).
hal::Expected<ObjMesh> load_obj(const std::filesystem::path& path, const ObjOptions& options = {});

// The OBJ text of a mesh ("v x y z" lines then "f a b c" lines).
std::string obj_text(const mesh::Mesh& mesh);
// Writes the mesh to `path` atomically (see above), under the programs' output rule
// (twister/hal/output_file.hpp): a new file, or with `force` over an OBJ; never over a
// journal, a checkpoint, a locked file (a running station's journal or base model)
// or anything else. io_error: cannot write; failed_precondition: refused.
hal::Expected<void> save_obj(const std::filesystem::path& path, const mesh::Mesh& mesh,
                             bool force = false);

}  // namespace twister::meshio
