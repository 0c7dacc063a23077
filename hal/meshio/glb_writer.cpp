// Binary glTF through tinygltf: positions upright (+Y) and centred, metres; normals
// rotated with them; one pbrMetallicRoughness material.
#include <tiny_gltf.h>

#include <cstring>
#include <glm/geometric.hpp>
#include <sstream>
#include <vector>

#include "export_file.hpp"
#include "export_frame.hpp"
#include "twister/mesh/vertex_normals.hpp"
#include "twister/meshio/mesh_export.hpp"

namespace twister::meshio {
namespace {

// The drawn vertices: positions, normals (both rotated) and triangles.
struct Drawn {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<std::uint32_t> indices;
};

hal::Expected<void> check_shading(const mesh::Mesh& mesh, const GlbShading& s) {
  bool fits = s.normals.size() == 3 * s.source.size() && s.indices.size() % 3 == 0;
  for (std::size_t i = 0; fits && i < s.source.size(); ++i)
    fits = s.source[i] < mesh.vertex_count();
  for (std::size_t i = 0; fits && i < s.indices.size(); ++i) fits = s.indices[i] < s.source.size();
  if (fits) return {};
  return hal::make_error(StatusCode::invalid_argument, "the shading does not fit the mesh");
}

Drawn drawn_vertices(const mesh::Mesh& mesh, const GlbShading& s, const internal::UprightFrame& f) {
  Drawn d;
  std::vector<std::uint32_t> source;
  std::vector<float> nx, ny, nz;
  if (s.source.empty()) {
    nx.resize(mesh.vertex_count());
    ny.resize(mesh.vertex_count());
    nz.resize(mesh.vertex_count());
    (void)mesh::compute_vertex_normals(mesh, {nx, ny, nz});
    source.resize(mesh.vertex_count());
    for (std::uint32_t i = 0; i < source.size(); ++i) source[i] = i;
    const auto idx = mesh.triangle_indices();
    d.indices.assign(idx.begin(), idx.end());
  } else {
    source.assign(s.source.begin(), s.source.end());
    d.indices.assign(s.indices.begin(), s.indices.end());
  }
  d.positions.reserve(3 * source.size());
  d.normals.reserve(3 * source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    const glm::dvec3 p = f.apply(glm::dvec3(mesh.position(source[i])));
    glm::dvec3 n = s.source.empty()
                       ? glm::dvec3(nx[source[i]], ny[source[i]], nz[source[i]])
                       : glm::dvec3(s.normals[3 * i], s.normals[3 * i + 1], s.normals[3 * i + 2]);
    n = f.rotation * n;
    const double len = glm::length(n);
    // glTF wants unit normals: a vertex on no triangle of area gets the up direction.
    n = len > 1e-12 ? n / len : glm::dvec3(0, 1, 0);
    for (int k = 0; k < 3; ++k) {
      d.positions.push_back(static_cast<float>(p[k]));
      d.normals.push_back(static_cast<float>(n[k]));
    }
  }
  return d;
}

// Appends `bytes` to the buffer (4-byte aligned) and returns its view's index.
int add_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  data.resize(data.size() + size);
  if (size > 0) std::memcpy(data.data() + view.byteOffset, bytes, size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int add_accessor(tinygltf::Model& model, int view, int component, std::size_t count, int type) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component;
  a.count = count;
  a.type = type;
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size() - 1);
}

void add_material(tinygltf::Model& model, const ExportOptions& o) {
  tinygltf::Material material;
  material.name = "twister clay";
  material.pbrMetallicRoughness.baseColorFactor = {o.base_color[0], o.base_color[1],
                                                   o.base_color[2], o.base_color[3]};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = o.roughness;
  material.doubleSided = false;
  model.materials.push_back(material);
}

tinygltf::Model gltf_model(const Drawn& d, const ExportOptions& o) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "twister-station (metres, +Y up, centred)";
  model.buffers.resize(1);
  const std::size_t count = d.positions.size() / 3;
  const int pos = add_view(model, d.positions.data(), d.positions.size() * sizeof(float),
                           TINYGLTF_TARGET_ARRAY_BUFFER);
  const int nrm = add_view(model, d.normals.data(), d.normals.size() * sizeof(float),
                           TINYGLTF_TARGET_ARRAY_BUFFER);
  const int idx = add_view(model, d.indices.data(), d.indices.size() * sizeof(std::uint32_t),
                           TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] =
      add_accessor(model, pos, TINYGLTF_COMPONENT_TYPE_FLOAT, count, TINYGLTF_TYPE_VEC3);
  // Required for POSITION: the float positions' own extremes.
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (std::size_t i = 0; i < d.positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], static_cast<double>(d.positions[i]));
    hi[i % 3] = std::max(hi[i % 3], static_cast<double>(d.positions[i]));
  }
  model.accessors.back().minValues = lo;
  model.accessors.back().maxValues = hi;
  primitive.attributes["NORMAL"] =
      add_accessor(model, nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, count, TINYGLTF_TYPE_VEC3);
  primitive.indices = add_accessor(model, idx, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                   d.indices.size(), TINYGLTF_TYPE_SCALAR);
  primitive.material = 0;
  add_material(model, o);
  tinygltf::Mesh mesh;
  mesh.name = "sculpture";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "sculpture";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

}  // namespace

hal::Expected<std::string> glb_bytes(const mesh::Mesh& mesh, const ExportOptions& options,
                                     const GlbShading& shading, bool binary) {
  if (mesh.triangle_count() == 0) {
    return hal::make_error(StatusCode::invalid_argument, "the mesh has no triangles");
  }
  if (auto fits = check_shading(mesh, shading); !fits) return fits.error();
  auto frame = internal::upright_frame(mesh, options.up, glm::dvec3(0, 1, 0));
  if (!frame) return frame.error();
  tinygltf::Model model = gltf_model(drawn_vertices(mesh, shading, *frame), options);
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, false, binary)) {
    return hal::make_error(StatusCode::io_error, "glTF: tinygltf could not encode the mesh");
  }
  return out.str();
}

hal::Expected<ExportReport> write_glb(const std::string& path, const mesh::Mesh& mesh,
                                      const ExportOptions& options, const GlbShading& shading) {
  auto bytes = glb_bytes(mesh, options, shading, true);
  if (!bytes) return hal::Error{bytes.error().status, path + ": " + bytes.error().message};
  auto frame = internal::upright_frame(mesh, options.up, glm::dvec3(0, 1, 0));
  ExportReport report;
  report.path = path;
  CheckOptions topology = options.check;
  topology.intersections = false;
  report.check = check_mesh(mesh, topology);
  report.units = "m";
  report.size = frame->hi - frame->lo;
  report.moved_by = frame->offset;
  report.bytes = bytes->size();
  if (auto written = internal::write_export_file(path, *bytes, hal::OutputKind::glb, options.force);
      !written) {
    return written.error();
  }
  return report;
}

}  // namespace twister::meshio
