// Exports a visitor can use: binary glTF (.glb) and binary STL of a model, upright,
// centred on the origin, in stated units, plus the closed/manifold check that runs
// before an STL is written (issue 25).
//
// Frames and units. The mesh is in the model's frame (the station's object frame,
// metres). `ExportOptions::up` is the model's up in that frame: +Z when the station
// has a calibrated work frame ([tracker.calibration.work_frame], +Z = X x Y), -Z for an
// uncalibrated station (the transmitter frame, +Z down). Each writer rotates the model
// so that `up` becomes its format's up and moves its bounding box's centre to the origin:
//   glTF (.glb): +Y up, metres (glTF 2.0 says so), one material (pbrMetallicRoughness,
//                a warm clay colour, not metallic), smooth vertex normals;
//   STL:         +Z up (what slicers and printers expect), millimetres (stated in the
//                80-byte header: "twister-station export, units mm, +Z up, ...").
// The rotation is the smallest one taking `up` to the format's up (about their cross
// product), so a model whose up is already the format's is only moved.
//
// Files. Every writer writes a temporary in the target's directory, fsyncs it and
// renames it into place (hal::PosixFileSink), and never replaces a file it did not
// create: an existing target is refused (failed_precondition, naming it) unless this
// process wrote it (same device and inode as a file a writer here committed) or,
// with `force`, it is a file of the same kind (the programs' output rule,
// twister/hal/output_file.hpp: never a journal, checkpoint or locked file).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <string>

#include "twister/hal/expected.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::meshio {

// What check_mesh() finds in the triangles' topology (edges are unordered vertex
// pairs; positions only matter for degenerate triangles and self-intersections).
struct MeshCheck {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t edges = 0;                 // distinct edges
  std::size_t open_edges = 0;            // on exactly one triangle (a hole's rim)
  std::size_t non_manifold_edges = 0;    // on three or more triangles
  std::size_t misoriented_edges = 0;     // two triangles that run the edge the same way
  std::size_t degenerate_triangles = 0;  // zero area or a repeated vertex
  // Pairs of triangles sharing no vertex whose interiors cross (uniform grid over the
  // bounding box, exact-enough triangle-triangle tests in doubles). Not counted when
  // the mesh has more than ExportOptions::max_intersection_triangles triangles.
  std::size_t self_intersections = 0;
  bool intersections_checked = false;

  // Closed: no open edge. Manifold: no edge on more than two triangles, consistently
  // oriented. Both: a watertight solid a printer can fill (self-intersections aside).
  bool closed() const { return open_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0 && misoriented_edges == 0; }
  bool watertight() const { return closed() && manifold() && degenerate_triangles == 0; }
};

struct CheckOptions {
  bool intersections = true;                        // count self-intersections
  std::size_t max_intersection_triangles = 400000;  // above this, skip that count
};

// The topology and (optionally) self-intersection counts of `mesh`. Allocates
// (host-side tool; O(T log T) for the edges, about O(T) for the grid).
MeshCheck check_mesh(const mesh::Mesh& mesh, const CheckOptions& options = {});

// One line for logs and the CLI: "closed, manifold: 0 open edges, 0 non-manifold
// edges, 0 misoriented edges, 0 degenerate triangles, 0 self-intersections".
std::string describe(const MeshCheck& check);

struct ExportOptions {
  glm::vec3 up{0.0F, 0.0F, 1.0F};  // the model's up in its own frame (see above)
  bool force = false;              // replace an existing file of the same kind
  CheckOptions check;              // what write_stl() checks first
  // glTF base colour (linear RGBA) and roughness: a warm clay by default.
  float base_color[4] = {0.80F, 0.55F, 0.42F, 1.0F};
  float roughness = 0.65F;
};

// What a writer did.
struct ExportReport {
  std::string path;
  MeshCheck check;           // write_stl: always; write_glb: topology only
  glm::dvec3 size{0.0};      // the written bounding box's extent, in the file's units
  glm::dvec3 moved_by{0.0};  // what was added to the rotated positions (model units)
  const char* units = "";    // "m" (glTF) or "mm" (STL)
  std::size_t bytes = 0;
};

// Binary STL (little-endian, 80-byte header, one facet normal per triangle), +Z up,
// millimetres. The check runs first and is in the report; an open or non-manifold
// mesh is still written (a visitor's sculpture is never thrown away), the caller
// decides what to say. Errors: invalid_argument (no triangles, `up` zero or not
// finite, a position not finite), failed_precondition (the target is refused, see
// above), io_error (cannot write); every message names the path.
hal::Expected<ExportReport> write_stl(const std::string& path, const mesh::Mesh& mesh,
                                      const ExportOptions& options = {});

// Optional crease-aware shading for write_glb (e.g. the display's: a crease's two
// sides are separate vertices): per drawn vertex its source vertex in the mesh and
// its normal (3 floats), and the drawn triangles over those vertices. Empty: smooth
// area-weighted normals over the mesh's own vertices.
struct GlbShading {
  std::span<const std::uint32_t> source;
  std::span<const float> normals;
  std::span<const std::uint32_t> indices;
};

// Binary glTF 2.0: one mesh, one primitive (POSITION, NORMAL, uint32 indices), one
// material (pbrMetallicRoughness), one node, one scene; +Y up, metres. Errors as
// write_stl (invalid_argument also: shading that does not fit the mesh).
hal::Expected<ExportReport> write_glb(const std::string& path, const mesh::Mesh& mesh,
                                      const ExportOptions& options = {},
                                      const GlbShading& shading = {});

// The .glb file's bytes (no file), for tests and the display's .gltf variant:
// `binary` false gives .gltf JSON with the buffer embedded as a data URI.
hal::Expected<std::string> glb_bytes(const mesh::Mesh& mesh, const ExportOptions& options,
                                     const GlbShading& shading = {}, bool binary = true);

}  // namespace twister::meshio
