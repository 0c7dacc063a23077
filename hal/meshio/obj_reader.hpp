// The strict OBJ reader's internals (private to hal/meshio; see obj_file.hpp):
// pass 1 checks every statement and counts, the mesh is allocated once, pass 2
// fills the positions, pass 3 the triangles (polygons checked and fanned), so a face
// may name a vertex defined after it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "obj_lines.hpp"
#include "twister/hal/expected.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::meshio::internal {

bool blank(char c);

// Whitespace-separated words of one line; a word starting with '#' ends it.
class Words {
 public:
  explicit Words(std::string_view line) : rest_(line) {}
  bool next(std::string_view& word);

 private:
  std::string_view rest_;
};

// A whole word as a finite float (an optional '+'; no trailing characters).
bool parse_number(std::string_view word, float& out);

struct Counts {
  std::int64_t v = 0, vt = 0, vn = 0;
};

enum class Kind : std::uint8_t { none, vertex, texture, normal, param, face, ignored, skipped };

Kind kind_of(std::string_view keyword);

// One read of one source. Errors name the line: "line N: what".
class ObjReader {
 public:
  ObjReader(LineSource& lines, const ObjOptions& options) : lines_(lines), options_(options) {}
  hal::Expected<ObjMesh> read();

 private:
  hal::Error error() const;
  bool check_numbers(Words& words, std::string_view keyword, float* xyz);
  // One reference "v[/vt][/vn]" -> the 0-based vertex index (vt, vn only checked).
  bool reference(std::string_view word, std::uint32_t& vertex);
  bool element(std::string_view text, std::int64_t defined, std::int64_t total, const char* what,
               std::int64_t& index);
  // Pass 1 for one line: checks it and counts what it defines.
  bool count_line(std::string_view line);
  bool count_pass();
  // Pass 2 (positions) or 3 (faces).
  bool fill_pass(mesh::Mesh& mesh, bool faces);
  bool fill_line(std::string_view line, mesh::Mesh& mesh, bool faces);
  bool add_face(Words& words, mesh::Mesh& mesh);
  // A polygon of 4+ vertices: fan triangles when convex along its Newell normal.
  bool add_polygon(mesh::Mesh& mesh);

  LineSource& lines_;
  const ObjOptions& options_;
  Counts defined_;  // elements defined so far in the current pass
  Counts total_;    // all of them (after pass 1)
  bool counted_ = false;
  std::size_t triangles_ = 0;
  std::size_t polygons_ = 0;
  std::size_t skipped_ = 0;
  std::vector<std::uint32_t> polygon_;
  std::string problem_;
};

}  // namespace twister::meshio::internal
