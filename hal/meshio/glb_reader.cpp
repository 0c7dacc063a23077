#include "twister/meshio/glb_reader.hpp"

#include <sys/stat.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <glm/vec3.hpp>
#include <vector>

namespace twister::meshio {
namespace {

hal::Error error(StatusCode code, const std::string& path, const std::string& what) {
  return hal::Error{code, path + ": " + what};
}

// The bytes an accessor reads: its view's buffer, offset and stride, checked.
struct Span {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

bool accessor_span(const tinygltf::Model& m, int index, std::size_t element_bytes, Span& out) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.accessors.size()) return false;
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= m.bufferViews.size())
    return false;
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m.buffers.size()) return false;
  const std::vector<unsigned char>& b = m.buffers[static_cast<std::size_t>(v.buffer)].data;
  const std::size_t stride = v.byteStride != 0 ? v.byteStride : element_bytes;
  if (stride < element_bytes || v.byteOffset > b.size() || v.byteLength > b.size() - v.byteOffset)
    return false;
  if (a.count == 0) return false;
  const std::size_t need = a.byteOffset + (a.count - 1) * stride + element_bytes;
  if (a.byteOffset > v.byteLength || need > v.byteLength || need < a.byteOffset) return false;
  out = {b.data() + v.byteOffset + a.byteOffset, stride, a.count};
  return true;
}

std::size_t index_bytes(int component) {
  switch (component) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return 4;
    default:
      return 0;
  }
}

std::uint32_t read_index(const unsigned char* p, std::size_t bytes) {
  if (bytes == 1) return *p;
  if (bytes == 2) {
    std::uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// Nothing outside the .glb is read: no external buffer or image file, no image decoded
// (the display needs the triangles alone).
bool no_file(const std::string&, void*) { return false; }
std::string same_path(const std::string& p, void*) { return p; }
bool no_read(std::vector<unsigned char>*, std::string* err, const std::string& p, void*) {
  if (err != nullptr) *err += "refused to read " + p + " (only the .glb itself is read)";
  return false;
}
bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err != nullptr) *err += "writing refused";
  return false;
}
bool no_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
              const unsigned char*, int, void*) {
  return true;  // images are skipped, not decoded
}

struct Triangles {
  std::vector<float> xyz;
  std::vector<std::uint32_t> indices;
};

// Appends one primitive's triangles. "": done; else why it is malformed.
std::string append(const tinygltf::Model& m, const tinygltf::Primitive& p,
                   const GlbReadLimits& limits, Triangles& out, bool& too_large) {
  const auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) return "a primitive without POSITION";
  if (pos->second < 0 || static_cast<std::size_t>(pos->second) >= m.accessors.size())
    return "POSITION names no accessor";
  const tinygltf::Accessor& pa = m.accessors[static_cast<std::size_t>(pos->second)];
  if (pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pa.type != TINYGLTF_TYPE_VEC3)
    return "POSITION is not float VEC3";
  Span ps;
  if (!accessor_span(m, pos->second, 12, ps)) return "POSITION reads outside its buffer";
  const std::size_t base = out.xyz.size() / 3;
  if (base + ps.count > limits.max_vertices) {
    too_large = true;
    return "more than " + std::to_string(limits.max_vertices) + " vertices";
  }
  std::vector<std::uint32_t> local;
  if (p.indices >= 0) {
    if (static_cast<std::size_t>(p.indices) >= m.accessors.size()) return "indices out of range";
    const tinygltf::Accessor& ia = m.accessors[static_cast<std::size_t>(p.indices)];
    const std::size_t bytes = index_bytes(ia.componentType);
    if (bytes == 0 || ia.type != TINYGLTF_TYPE_SCALAR) return "indices are not unsigned scalars";
    Span is;
    if (!accessor_span(m, p.indices, bytes, is)) return "indices read outside their buffer";
    if (is.count % 3 != 0) return "an index count that is not a multiple of 3";
    local.reserve(is.count);
    for (std::size_t i = 0; i < is.count; ++i)
      local.push_back(read_index(is.data + i * is.stride, bytes));
  } else {
    if (ps.count % 3 != 0) return "a vertex count that is not a multiple of 3";
    for (std::size_t i = 0; i < ps.count; ++i) local.push_back(static_cast<std::uint32_t>(i));
  }
  if (out.indices.size() / 3 + local.size() / 3 > limits.max_triangles) {
    too_large = true;
    return "more than " + std::to_string(limits.max_triangles) + " triangles";
  }
  for (std::size_t i = 0; i < ps.count; ++i) {
    float v[3];
    std::memcpy(v, ps.data + i * ps.stride, 12);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      return "a position that is not finite";
    out.xyz.insert(out.xyz.end(), v, v + 3);
  }
  for (const std::uint32_t k : local) {
    if (k >= ps.count) return "an index past the vertices";
    out.indices.push_back(static_cast<std::uint32_t>(base) + k);
  }
  return {};
}

}  // namespace

hal::Expected<std::unique_ptr<MeshBuffer>> read_glb(const std::string& path,
                                                    const GlbReadLimits& limits) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return error(StatusCode::io_error, path, std::string("cannot read: ") + std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) return error(StatusCode::io_error, path, "not a regular file");
  if (static_cast<std::uint64_t>(st.st_size) > limits.max_file_bytes) {
    return error(StatusCode::resource_exhausted, path,
                 std::to_string(st.st_size) + " bytes, more than the limit of " +
                     std::to_string(limits.max_file_bytes));
  }
  std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    return error(StatusCode::io_error, path, std::string("cannot read: ") + std::strerror(errno));
  }
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  if (got != bytes.size()) return error(StatusCode::io_error, path, "short read");
  return parse_glb(bytes, path, limits);
}

hal::Expected<std::unique_ptr<MeshBuffer>> parse_glb(std::span<const unsigned char> bytes,
                                                     const std::string& path,
                                                     const GlbReadLimits& limits) {
  if (bytes.size() > limits.max_file_bytes) {
    return error(StatusCode::resource_exhausted, path,
                 std::to_string(bytes.size()) + " bytes, more than the limit of " +
                     std::to_string(limits.max_file_bytes));
  }
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{no_file, same_path, no_read, no_write, nullptr});
  loader.SetImageLoader(no_image, nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  if (bytes.size() < 20 || bytes.size() > 0xFFFFFFFFu ||
      !loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                   static_cast<unsigned int>(bytes.size()))) {
    return error(StatusCode::invalid_argument, path,
                 "not a binary glTF tinygltf reads: " + (err.empty() ? warn : err));
  }
  Triangles t;
  for (const tinygltf::Mesh& mesh : model.meshes) {
    for (const tinygltf::Primitive& p : mesh.primitives) {
      if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES) continue;  // lines, points
      bool too_large = false;
      if (std::string why = append(model, p, limits, t, too_large); !why.empty()) {
        return error(too_large ? StatusCode::resource_exhausted : StatusCode::invalid_argument,
                     path, why);
      }
    }
  }
  if (t.indices.empty()) return error(StatusCode::invalid_argument, path, "no triangles");
  auto buffer = std::make_unique<MeshBuffer>(t.xyz.size() / 3, t.indices.size() / 3);
  mesh::Mesh& m = buffer->mesh();
  for (std::size_t i = 0; i < t.xyz.size(); i += 3) {
    if (!m.add_vertex({t.xyz[i], t.xyz[i + 1], t.xyz[i + 2]}).ok())
      return error(StatusCode::resource_exhausted, path, "the mesh is full");
  }
  for (std::size_t i = 0; i < t.indices.size(); i += 3) {
    if (!m.add_triangle(t.indices[i], t.indices[i + 1], t.indices[i + 2]).ok())
      return error(StatusCode::invalid_argument, path, "a triangle the mesh refuses");
  }
  return buffer;
}

}  // namespace twister::meshio
