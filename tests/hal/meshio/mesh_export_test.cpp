// STL and binary glTF of a model: upright, centred, in their units, the glTF with a
// material (reloaded with tinygltf, a reader we did not write); the file rule (never
// over a file this process did not write); the thumbnail.
#include "twister/meshio/mesh_export.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>
#include <iterator>
#include <vector>

#include "twister/meshio/glb_reader.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/thumbnail.hpp"

namespace twister::meshio {
namespace {

namespace fs = std::filesystem;

// A tapered cylinder (narrow end toward +axis, its "up") lying along `axis` (x or -z)
// and moved away from the origin: what the station's model frame holds.
struct Sculpture {
  MeshBuffer buffer{cylinder_vertices(6, 24), cylinder_triangles(6, 24)};
  Sculpture(glm::vec3 axis, glm::vec3 offset) {
    mesh::Mesh& m = buffer.mesh();
    EXPECT_TRUE(make_cylinder(m, 6, 24, 0.05F, 0.2F).ok());
    // Taper: radius shrinks to 30% at the top (z = +0.2).
    for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
      glm::vec3 p = m.position(i);
      const float k = 1.0F - 0.7F * (p.z + 0.2F) / 0.4F;
      p.x *= k;
      p.y *= k;
      // Lay the z axis along `axis` (x: z->x, x->-z; -z: flip z and y).
      glm::vec3 q = axis.x > 0.5F ? glm::vec3(p.z, p.y, -p.x) : glm::vec3(p.x, -p.y, -p.z);
      m.set_position(i, q + offset);
    }
  }
};

ExportOptions with_up(glm::vec3 up, bool force = false) {
  ExportOptions o;
  o.up = up;
  o.force = force;
  return o;
}

fs::path scratch(const char* name) {
  const fs::path dir = fs::temp_directory_path() / "twister_mesh_export_test";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  fs::remove(p);
  return p;
}

std::vector<char> slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

float f32_at(const std::vector<char>& b, std::size_t offset) {
  float f = 0;
  std::memcpy(&f, b.data() + offset, 4);
  return f;
}

TEST(MeshExport, StlIsBinaryUprightCentredInMillimetres) {
  const Sculpture s(glm::vec3(1, 0, 0), glm::vec3(1.0F, 2.0F, 3.0F));
  const fs::path path = scratch("upright.stl");
  const auto report = write_stl(path, s.buffer.mesh(), with_up(glm::vec3(1, 0, 0)));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_TRUE(report->check.watertight()) << describe(report->check);
  EXPECT_EQ(report->check.self_intersections, 0U);
  EXPECT_STREQ(report->units, "mm");
  const std::vector<char> b = slurp(path);
  const std::size_t t = s.buffer.mesh().triangle_count();
  ASSERT_EQ(b.size(), 84 + 50 * t);
  EXPECT_EQ(std::string(b.data(), 22), "twister-station export");
  EXPECT_NE(std::string(b.data(), 80).find("units mm, +Z up"), std::string::npos);
  std::uint32_t count = 0;
  std::memcpy(&count, b.data() + 80, 4);
  EXPECT_EQ(count, t);
  glm::dvec3 lo(1e9), hi(-1e9);
  double top_radius = 0.0, bottom_radius = 0.0;
  for (std::size_t i = 0; i < t; ++i) {
    for (std::size_t v = 0; v < 3; ++v) {
      const std::size_t at = 84 + 50 * i + 12 + 12 * v;
      const glm::dvec3 p(f32_at(b, at), f32_at(b, at + 4), f32_at(b, at + 8));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
      const double r = std::hypot(p.x, p.y);
      if (p.z > 199.0) top_radius = std::max(top_radius, r);
      if (p.z < -199.0) bottom_radius = std::max(bottom_radius, r);
    }
  }
  // 0.4 m tall along +Z, centred: -200..200 mm; 0.1 m wide.
  EXPECT_NEAR(lo.z, -200.0, 1e-3);
  EXPECT_NEAR(hi.z, 200.0, 1e-3);
  EXPECT_NEAR(lo.x + hi.x, 0.0, 1e-3);
  EXPECT_NEAR(lo.y + hi.y, 0.0, 1e-3);
  EXPECT_NEAR(hi.x - lo.x, 100.0, 0.1);
  // Upright: the narrow end is up.
  EXPECT_NEAR(top_radius, 15.0, 0.1);
  EXPECT_NEAR(bottom_radius, 50.0, 0.1);
  EXPECT_NEAR(report->size.z, 400.0, 1e-3);
}

TEST(MeshExport, GlbReloadsWithTinygltfUprightWithAMaterial) {
  // An uncalibrated station's model frame: up is -Z.
  const Sculpture s(glm::vec3(0, 0, -1), glm::vec3(0.3F, -0.2F, 0.5F));
  const fs::path path = scratch("upright.glb");
  const auto report = write_glb(path, s.buffer.mesh(), with_up(glm::vec3(0, 0, -1)));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_STREQ(report->units, "m");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) << err;
  ASSERT_EQ(model.materials.size(), 1U);
  const auto& pbr = model.materials[0].pbrMetallicRoughness;
  EXPECT_EQ(pbr.metallicFactor, 0.0);
  EXPECT_GT(pbr.baseColorFactor[0], pbr.baseColorFactor[2]);  // warm
  ASSERT_EQ(model.meshes.size(), 1U);
  const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
  EXPECT_EQ(prim.material, 0);
  ASSERT_TRUE(prim.attributes.count("NORMAL"));
  const tinygltf::Accessor& pos =
      model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))];
  // +Y up, metres, centred.
  EXPECT_NEAR(pos.minValues[1], -0.2, 1e-6);
  EXPECT_NEAR(pos.maxValues[1], 0.2, 1e-6);
  EXPECT_NEAR(pos.minValues[0] + pos.maxValues[0], 0.0, 1e-6);
  EXPECT_NEAR(pos.minValues[2] + pos.maxValues[2], 0.0, 1e-6);
  // The narrow end is at +Y.
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(pos.bufferView)];
  const auto* xyz = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset +
                                                   pos.byteOffset);
  double top_radius = 0.0;
  for (std::size_t i = 0; i < pos.count; ++i) {
    if (xyz[3 * i + 1] > 0.199F)
      top_radius = std::max(top_radius, std::hypot(double(xyz[3 * i]), double(xyz[3 * i + 2])));
  }
  EXPECT_NEAR(top_radius, 0.015, 1e-4);
}

// read_glb (the display's attract showcase) gives back what write_glb wrote: the same
// triangles, upright (+Y) and centred; bad files are refused with the file named,
// never a crash.
TEST(GlbReader, ReadsBackWhatTheWriterWroteAndRefusesBadFiles) {
  const Sculpture s(glm::vec3(0, 0, -1), glm::vec3(0.3F, -0.2F, 0.5F));
  const fs::path path = scratch("readback.glb");
  ASSERT_TRUE(write_glb(path, s.buffer.mesh(), with_up(glm::vec3(0, 0, -1))));
  const auto read = read_glb(path.string());
  ASSERT_TRUE(read) << read.error().message;
  const mesh::Mesh& m = (*read)->mesh();
  EXPECT_EQ(m.triangle_count(), s.buffer.mesh().triangle_count());
  EXPECT_GE(m.vertex_count(), s.buffer.mesh().vertex_count());
  glm::vec3 lo(1e9F), hi(-1e9F);
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    lo = glm::min(lo, m.position(i));
    hi = glm::max(hi, m.position(i));
  }
  EXPECT_NEAR(lo.y, -0.2F, 1e-5F);  // the cylinder's axis is +Y now
  EXPECT_NEAR(hi.y, 0.2F, 1e-5F);
  EXPECT_NEAR(lo.x + hi.x, 0.0F, 1e-5F);
  // Bounded: counts over the limits are refused before anything is copied.
  GlbReadLimits small;
  small.max_triangles = 10;
  const auto too_many = read_glb(path.string(), small);
  ASSERT_FALSE(too_many);
  EXPECT_EQ(too_many.error().status.code(), StatusCode::resource_exhausted);
  small = {};
  small.max_file_bytes = 100;
  EXPECT_EQ(read_glb(path.string(), small).error().status.code(), StatusCode::resource_exhausted);
  // Cut short, garbage, missing: refused, named.
  const std::vector<char> bytes = slurp(path);
  const fs::path cut = scratch("cut.glb");
  std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
  const auto torn = read_glb(cut.string());
  ASSERT_FALSE(torn);
  EXPECT_EQ(torn.error().status.code(), StatusCode::invalid_argument);
  EXPECT_NE(torn.error().message.find(cut.string()), std::string::npos);
  const fs::path junk = scratch("junk.glb");
  std::ofstream(junk, std::ios::binary) << "glTF this is not";
  EXPECT_EQ(read_glb(junk.string()).error().status.code(), StatusCode::invalid_argument);
  EXPECT_EQ(read_glb(scratch("none.glb").string()).error().status.code(), StatusCode::io_error);
}

TEST(MeshExport, NeverReplacesAFileItDidNotWrite) {
  const Sculpture s(glm::vec3(1, 0, 0), glm::vec3(0.0F));
  const fs::path path = scratch("theirs.stl");
  { std::ofstream(path) << "solid someone else's\n"; }
  auto refused = write_stl(path, s.buffer.mesh(), with_up(glm::vec3(1, 0, 0)));
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().status.code(), StatusCode::failed_precondition);
  EXPECT_NE(refused.error().message.find(path.string()), std::string::npos);
  EXPECT_EQ(slurp(path).size(), 21U);  // untouched
  // A journal is never replaced, not even with force.
  const fs::path journal = scratch("journal.stl");
  { std::ofstream(journal) << "TWJL\x02"; }
  EXPECT_FALSE(write_glb(journal.string(), s.buffer.mesh(), with_up(glm::vec3(0, 0, 1), true)));
  // Its own file (this process wrote it) it may write again; a new one too.
  const fs::path own = scratch("own.glb");
  ASSERT_TRUE(write_glb(own, s.buffer.mesh()));
  EXPECT_TRUE(write_glb(own, s.buffer.mesh()));
  // No temporaries left behind.
  for (const auto& entry : fs::directory_iterator(own.parent_path())) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

TEST(MeshExport, BadInputIsRefusedWithAReason) {
  MeshBuffer empty(4, 4);
  const auto none = write_stl(scratch("empty.stl"), empty.mesh());
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().status.code(), StatusCode::invalid_argument);
  const Sculpture s(glm::vec3(1, 0, 0), glm::vec3(0.0F));
  const auto zero_up = write_glb(scratch("zero.glb"), s.buffer.mesh(), with_up(glm::vec3(0.0F)));
  ASSERT_FALSE(zero_up);
  EXPECT_NE(zero_up.error().message.find("up direction"), std::string::npos);
  const std::uint32_t bad_source[] = {999999};
  const float normals[] = {0, 0, 1};
  const auto bad = glb_bytes(s.buffer.mesh(), {}, {bad_source, normals, {}});
  EXPECT_FALSE(bad);
}

TEST(MeshExport, OpenMeshIsWrittenAndReported) {
  MeshBuffer grid(grid_vertices(5), grid_triangles(5));
  ASSERT_TRUE(make_grid(grid.mesh(), 5, 0.1F).ok());
  const auto report = write_stl(scratch("open.stl"), grid.mesh());
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report->check.open_edges, 16U);
  EXPECT_FALSE(report->check.closed());
}

TEST(Thumbnail, UprightFramedAndShaded) {
  const Sculpture s(glm::vec3(1, 0, 0), glm::vec3(1.0F, 2.0F, 3.0F));
  const auto image = render_thumbnail(s.buffer.mesh(), glm::vec3(1, 0, 0), 128);
  ASSERT_TRUE(image) << image.error().message;
  ASSERT_EQ(image->rgba.size(), 128U * 128U * 4U);
  // Framed: the model covers a fair part of the picture, not all of it.
  EXPECT_GT(image->covered_pixels, 128U * 128U / 10);
  EXPECT_LT(image->covered_pixels, 128U * 128U * 3 / 4);
  // Upright: the model's rows near the top are narrower than near the bottom (the
  // narrow end up). Count the pixels differing from the background per row.
  auto width_of_row = [&](int y) {
    int n = 0;
    const std::uint8_t* row = image->rgba.data() + 4 * 128 * y;
    for (int x = 0; x < 128; ++x) {
      const std::uint8_t* p = row + 4 * x;
      if (p[0] > p[2] + 25) ++n;  // clay is warm, the background cool grey
    }
    return n;
  };
  int top = -1, bottom = -1;
  for (int y = 0; y < 128; ++y) {
    if (width_of_row(y) > 0) {
      if (top < 0) top = y;
      bottom = y;
    }
  }
  ASSERT_GE(top, 0);
  EXPECT_LT(width_of_row(top + 6), width_of_row(bottom - 6));
  EXPECT_GT(bottom - top, 128 / 2);  // tall thing, tall picture
  const fs::path png = scratch("thumbnail.png");
  ASSERT_TRUE(render_thumbnail_png(s.buffer.mesh(), glm::vec3(1, 0, 0), 256, png.string()));
  const std::vector<char> b = slurp(png);
  ASSERT_GT(b.size(), 8U);
  EXPECT_EQ(std::string(b.data() + 1, 3), "PNG");
  EXPECT_FALSE(render_thumbnail(s.buffer.mesh(), glm::vec3(1, 0, 0), 8));
}

}  // namespace
}  // namespace twister::meshio
