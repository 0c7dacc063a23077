#include "twister/meshio/obj_file.hpp"

#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace twister::meshio {
namespace {

// tinyobjloader reads a malformed number ("nan", "1.2.3", "x") as 0 without a
// word, which would silently corrupt the model; position lines are checked here
// first: 3 to 7 finite numbers (x y z [w] or x y z r g b).
std::string check_positions(std::string_view text) {
  std::size_t line_no = 0;
  while (!text.empty()) {
    ++line_no;
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    int count = 0;
    std::size_t pos = 1;
    for (;;) {
      while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t' || line[pos] == '\r'))
        ++pos;
      if (pos >= line.size()) break;
      float value = 0.0f;
      const auto [next, ec] = std::from_chars(line.data() + pos, line.data() + line.size(), value);
      const bool separated =
          next == line.data() + line.size() || *next == ' ' || *next == '\t' || *next == '\r';
      if (ec != std::errc() || !separated || !std::isfinite(value)) {
        return "line " + std::to_string(line_no) + ": vertex coordinate '" +
               std::string(
                   line.substr(pos, static_cast<std::size_t>(next - line.data()) - pos + 1)) +
               "' is not a finite number";
      }
      pos = static_cast<std::size_t>(next - line.data());
      ++count;
    }
    if (count < 3 || count > 7) {
      return "line " + std::to_string(line_no) + ": a vertex needs 3 coordinates";
    }
  }
  return {};
}

}  // namespace

ObjLoad parse_obj(std::string_view text, std::size_t spare_vertices, std::size_t spare_triangles) {
  ObjLoad out;
  if (std::string bad = check_positions(text); !bad.empty()) {
    out.status = StatusCode::invalid_argument;
    out.message = "OBJ " + bad;
    return out;
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(std::string(text), "", config)) {
    out.status = StatusCode::invalid_argument;
    out.message = "OBJ parse error: " + reader.Error();
    return out;
  }
  const auto& positions = reader.GetAttrib().vertices;
  const std::size_t vertices = positions.size() / 3;
  if (vertices == 0) {
    out.status = StatusCode::invalid_argument;
    out.message = "OBJ has no vertices";
    return out;
  }
  if (vertices > std::numeric_limits<std::uint32_t>::max()) {
    out.status = StatusCode::invalid_argument;
    out.message = "OBJ has too many vertices";
    return out;
  }
  std::size_t triangles = 0;
  for (const auto& shape : reader.GetShapes()) triangles += shape.mesh.indices.size() / 3;
  out.buffer = std::make_unique<MeshBuffer>(vertices + spare_vertices, triangles + spare_triangles);
  mesh::Mesh& m = out.buffer->mesh();
  for (std::size_t i = 0; i < vertices; ++i) {
    const glm::vec3 p{positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      out.status = StatusCode::invalid_argument;
      out.message = "OBJ vertex " + std::to_string(i + 1) + " is not finite";
      out.buffer.reset();
      return out;
    }
    (void)m.add_vertex(p);
  }
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (std::size_t f = 0; f + 2 < idx.size(); f += 3) {
      const int a = idx[f].vertex_index, b = idx[f + 1].vertex_index, c = idx[f + 2].vertex_index;
      if (a < 0 || b < 0 || c < 0 ||
          !m.add_triangle(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                          static_cast<std::uint32_t>(c))
               .ok()) {
        out.status = StatusCode::invalid_argument;
        out.message = "OBJ face " + std::to_string(f / 3 + 1) + " in '" + shape.name +
                      "' refers to a vertex that does not exist";
        out.buffer.reset();
        return out;
      }
    }
  }
  if (!reader.Warning().empty()) out.message = "OBJ warning: " + reader.Warning();
  return out;
}

ObjLoad load_obj(const std::filesystem::path& path, std::size_t spare_vertices,
                 std::size_t spare_triangles) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    ObjLoad out;
    out.status = StatusCode::io_error;
    out.message = "cannot open " + path.string();
    return out;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_obj(text.str(), spare_vertices, spare_triangles);
}

std::string obj_text(const mesh::Mesh& mesh) {
  std::string out;
  out.reserve(40 * mesh.vertex_count() + 30 * mesh.triangle_count());
  char line[128];
  for (std::uint32_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 p = mesh.position(i);
    const int n = std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p.x), double(p.y),
                                double(p.z));
    out.append(line, static_cast<std::size_t>(n));
  }
  const auto idx = mesh.triangle_indices();
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const int n = std::snprintf(line, sizeof line, "f %u %u %u\n", idx[t] + 1, idx[t + 1] + 1,
                                idx[t + 2] + 1);
    out.append(line, static_cast<std::size_t>(n));
  }
  return out;
}

Status save_obj(const std::filesystem::path& path, const mesh::Mesh& mesh, std::string& message) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const std::string text = obj_text(mesh);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) {
      message = "cannot write " + tmp.string();
      return StatusCode::io_error;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    message = "cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message();
    return StatusCode::io_error;
  }
  return ok_status();
}

}  // namespace twister::meshio
