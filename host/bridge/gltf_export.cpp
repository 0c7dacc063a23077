#include "gltf_export.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <sstream>

namespace twister::bridge {
namespace {

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
  std::memcpy(data.data() + view.byteOffset, bytes, size);
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

}  // namespace

hal::Expected<std::string> gltf_bytes(const MeshData& m, const ShadedMesh& shaded, bool binary) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "twister-bridge";
  model.buffers.resize(1);
  // One glTF vertex per drawn vertex: a crease's two sides keep their own normals.
  const std::size_t count = shaded.vertex_count();
  const std::vector<float>& normals = shaded.normals;
  std::vector<float> positions(3 * count);
  std::vector<double> lo(3, 1e300);
  std::vector<double> hi(3, -1e300);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t v = shaded.source[i];
    const float p[3] = {m.x[v], m.y[v], m.z[v]};
    for (std::size_t k = 0; k < 3; ++k) {
      positions[3 * i + k] = p[k];
      lo[k] = std::min(lo[k], static_cast<double>(p[k]));
      hi[k] = std::max(hi[k], static_cast<double>(p[k]));
    }
  }
  const int pos_view = add_view(model, positions.data(), positions.size() * sizeof(float),
                                TINYGLTF_TARGET_ARRAY_BUFFER);
  const int normal_view =
      add_view(model, normals.data(), normals.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  const int index_view =
      add_view(model, shaded.indices.data(), shaded.indices.size() * sizeof(std::uint32_t),
               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = add_accessor(model, pos_view, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                  count, TINYGLTF_TYPE_VEC3);
  model.accessors.back().minValues = lo;  // required for POSITION
  model.accessors.back().maxValues = hi;
  primitive.attributes["NORMAL"] = add_accessor(model, normal_view, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                count, TINYGLTF_TYPE_VEC3);
  primitive.indices = add_accessor(model, index_view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                   shaded.indices.size(), TINYGLTF_TYPE_SCALAR);
  tinygltf::Mesh mesh;
  mesh.name = "twister";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, false, binary)) {
    return hal::make_error(StatusCode::io_error, "glTF: tinygltf could not encode the mesh");
  }
  return out.str();
}

}  // namespace twister::bridge
