// A station's exhibit archive made for the attract showcase's tests (issue 25): one
// directory per visitor as hal/twister-station/exhibit_archive.cpp names and fills it
// (YYYYMMDDTHHMMSSZ-vNNNN-IIIIIIII with model.glb and record.json), written by
// hal/meshio's own .glb writer: a tall column (a cylinder, its axis up) and a wide
// disc, so a picture tells them apart and tells which way is up.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_export.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge::test {

struct ShowcaseArchive {
  std::filesystem::path dir;

  explicit ShowcaseArchive(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / name) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~ShowcaseArchive() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  // A cylinder of `radius` and `half_height` about its +Z, archived as visitor `visitor`
  // at `when` (YYYYMMDDTHHMMSS) with `strokes` in its record. Returns its name.
  std::string add(const char* when, unsigned visitor, float radius, float half_height,
                  unsigned strokes) {
    const std::string name = directory(when, visitor);
    std::filesystem::create_directories(dir / name);
    meshio::MeshBuffer b(meshio::cylinder_vertices(8, 48), meshio::cylinder_triangles(8, 48));
    EXPECT_TRUE(meshio::make_cylinder(b.mesh(), 8, 48, radius, half_height).ok());
    meshio::ExportOptions o;
    o.up = glm::vec3(0.0F, 0.0F, 1.0F);  // the column stands on its end
    const auto written = meshio::write_glb((dir / name / "model.glb").string(), b.mesh(), o);
    EXPECT_TRUE(written) << written.error().message;
    std::ofstream(dir / name / "record.json")
        << "{\n  \"format\": \"twister-sculpture-1\",\n  \"visitor\": " << visitor
        << ",\n  \"strokes\": " << strokes << ",\n  \"undos\": 0\n}\n";
    return name;
  }
  // A sculpted-looking one: a tall box twisted a quarter turn about its up axis and
  // bulging in its middle (the paper's Figure 6 gesture).
  std::string add_twisted(const char* when, unsigned visitor, unsigned strokes) {
    const std::string name = directory(when, visitor);
    std::filesystem::create_directories(dir / name);
    meshio::MeshBuffer b(meshio::box_vertices(24), meshio::box_triangles(24));
    EXPECT_TRUE(meshio::make_box(b.mesh(), 24, 0.05F).ok());
    mesh::Mesh& m = b.mesh();
    for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
      glm::vec3 p = m.position(i);
      const float t = p.z / 0.05F;  // -1 .. 1
      const float z = 0.15F * t;
      const float a = 0.8F * t;                       // radians of twist
      const float k = 1.0F + 0.35F * (1.0F - t * t);  // bulge
      const float x = k * (p.x * std::cos(a) - p.y * std::sin(a));
      const float y = k * (p.x * std::sin(a) + p.y * std::cos(a));
      m.set_position(i, glm::vec3(x, y, z));
    }
    meshio::ExportOptions o;
    o.up = glm::vec3(0.0F, 0.0F, 1.0F);
    const auto written = meshio::write_glb((dir / name / "model.glb").string(), m, o);
    EXPECT_TRUE(written) << written.error().message;
    std::ofstream(dir / name / "record.json")
        << "{\n  \"visitor\": " << visitor << ",\n  \"strokes\": " << strokes << "\n}\n";
    return name;
  }
  // An archive whose model.glb is not one.
  std::string add_bad(const char* when, unsigned visitor) {
    const std::string name = directory(when, visitor);
    std::filesystem::create_directories(dir / name);
    std::ofstream(dir / name / "model.glb") << "glTF, it says, but it is not";
    return name;
  }
  static std::string directory(const char* when, unsigned visitor) {
    char name[40];
    std::snprintf(name, sizeof name, "%sZ-v%04u-5c0000%02x", when, visitor, visitor & 0xFFu);
    return name;
  }
};

}  // namespace twister::bridge::test
