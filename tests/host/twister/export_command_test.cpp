// `twister export` end to end (issue 25, label exhibit): a journal written by a live
// SculptSession is replayed onto a closed model and exported; the STL is checked by
// Debian's admesh (a checker we did not write: no open or disconnected facets, one
// part, bounding box centred on the origin), the .glb reloads with tinygltf with a
// material; an open model is reported with its open-edge count; bad inputs exit 2.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "cli_test_support.hpp"
#include "core/session/session_harness.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister {
namespace {

using namespace session::test_support;
namespace fs = std::filesystem;

// A number admesh prints after `label` (e.g. "Min X = "), or NaN.
double admesh_value(const std::string& out, const std::string& label) {
  const std::size_t at = out.find(label);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(out.c_str() + at + label.size(), nullptr);
}

class ExportCommand : public ::testing::Test {
 protected:
  // Strokes pulling and twisting near the model's surface (the harness's hands).
  void record(Station& s, int strokes) {
    for (int k = 0; k < strokes; ++k) {
      const double x = -0.3 + 0.15 * (k % 5);
      s.hand(0, math::identity_frame({x, 0.1, 0.25}));
      s.button(kGrab0, true);
      (void)s.tick();
      s.hand(0, z_turn({x + 0.03, 0.12, 0.3}, 0.3));
      (void)s.tick();
      s.button(kGrab0, false);
      (void)s.tick();
    }
  }
  void SetUp() override {
    Station live(17);
    record(live, 5);
    host_test::write_file(dir_ / "visitor.twj", live.storage.bytes());
    ASSERT_EQ(host_test::run_twister("mesh sphere -n 24 --segments 32 --size 0.3 --out " +
                                     (dir_ / "base.obj").string())
                  .exit_code,
              0);
  }
  std::string journal() const { return (dir_ / "visitor.twj").string(); }
  host_test::ScratchDir dir_{"twister_export_test"};
};

TEST_F(ExportCommand, StlPassesAdmeshAndGlbReloadsWithAMaterial) {
  const fs::path out = dir_ / "out";
  const host_test::CommandRun r =
      host_test::run_twister("export " + journal() + " --base " + (dir_ / "base.obj").string() +
                             " --out " + out.string() + " --size 128");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("replayed 5 records"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("check closed, manifold: 0 open edges, 0 non-manifold edges"),
            std::string::npos)
      << r.out;
  ASSERT_TRUE(fs::exists(out / "visitor.glb"));
  ASSERT_TRUE(fs::exists(out / "visitor.stl"));
  ASSERT_TRUE(fs::exists(out / "visitor.png"));

  const host_test::CommandRun a =
      host_test::run_command("admesh " + (out / "visitor.stl").string());
  ASSERT_EQ(a.exit_code, 0) << a.out;
  EXPECT_NE(a.out.find("Binary STL file"), std::string::npos) << a.out;
  EXPECT_NE(a.out.find("units mm, +Z up"), std::string::npos) << a.out;
  EXPECT_TRUE(std::regex_search(a.out, std::regex(R"(Total disconnected facets\s*:\s*0\s+0)")))
      << a.out;
  EXPECT_TRUE(std::regex_search(a.out, std::regex(R"(Number of parts\s*:\s*1\b)"))) << a.out;
  EXPECT_TRUE(std::regex_search(a.out, std::regex(R"(Facets with 1 disconnected edge\s*:\s*0\s)")))
      << a.out;
  EXPECT_NE(a.out.find("No holes need to be filled."), std::string::npos) << a.out;
  for (const char* axis : {"X", "Y", "Z"}) {
    const double lo = admesh_value(a.out, std::string("Min ") + axis + " = ");
    const double hi = admesh_value(a.out, std::string("Max ") + axis + " = ");
    EXPECT_NEAR(lo + hi, 0.0, 0.01) << axis << " " << a.out;  // centred, mm
    EXPECT_GT(hi - lo, 500.0) << axis;                        // a 0.6 m sphere, warped, in mm
  }

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (out / "visitor.glb").string()))
      << err;
  ASSERT_EQ(model.materials.size(), 1U);
  EXPECT_EQ(model.meshes.at(0).primitives.at(0).material, 0);
  EXPECT_EQ(model.materials[0].pbrMetallicRoughness.metallicFactor, 0.0);
}

TEST_F(ExportCommand, OpenModelIsReportedWithItsOpenEdges) {
  meshio::MeshBuffer grid(17 * 17, 2 * 16 * 16);
  make_grid(grid.mesh(), 17);
  ASSERT_TRUE(meshio::save_obj(dir_ / "grid.obj", grid.mesh()).has_value());
  const std::string args = "export " + journal() + " --base " + (dir_ / "grid.obj").string() +
                           " --stl --out " + (dir_ / "open").string();
  const host_test::CommandRun r = host_test::run_twister(args);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("check open, manifold: 64 open edges"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("is not a watertight solid"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "open" / "visitor.glb"));  // only what was asked
  // --strict: the same, exit 1 (the file is written either way).
  const host_test::CommandRun strict = host_test::run_twister(args + " --strict --force");
  EXPECT_EQ(strict.exit_code, 1) << strict.out;
}

TEST_F(ExportCommand, BadInputsExitTwoAndNothingIsReplaced) {
  // No --base and no base.obj beside the journal.
  fs::create_directories(dir_ / "alone");
  fs::copy_file(journal(), dir_ / "alone" / "v.twj");
  const host_test::CommandRun no_base = host_test::run_twister(
      "export " + (dir_ / "alone" / "v.twj").string() + " --out " + (dir_ / "o1").string());
  EXPECT_EQ(no_base.exit_code, 2) << no_base.out;
  EXPECT_NE(no_base.out.find("no base model: pass --base"), std::string::npos) << no_base.out;
  // base.obj beside the journal is taken.
  fs::copy_file(dir_ / "base.obj", dir_ / "alone" / "base.obj");
  const host_test::CommandRun beside = host_test::run_twister(
      "export " + (dir_ / "alone" / "v.twj").string() + " --glb --out " + (dir_ / "o1").string());
  EXPECT_EQ(beside.exit_code, 0) << beside.out;
  // An existing file is refused before any work, and left alone.
  fs::create_directories(dir_ / "o2");
  std::ofstream(dir_ / "o2" / "visitor.stl") << "solid mine\n";
  const host_test::CommandRun exists =
      host_test::run_twister("export " + journal() + " --base " + (dir_ / "base.obj").string() +
                             " --out " + (dir_ / "o2").string());
  EXPECT_EQ(exists.exit_code, 2) << exists.out;
  EXPECT_NE(exists.out.find("exists"), std::string::npos) << exists.out;
  EXPECT_EQ(fs::file_size(dir_ / "o2" / "visitor.stl"), 11U);
  EXPECT_FALSE(fs::exists(dir_ / "o2" / "visitor.glb"));
  // A journal as the output's name: never replaced, not even with --force.
  fs::copy_file(journal(), dir_ / "o2" / "visitor.glb");
  const host_test::CommandRun journal_out =
      host_test::run_twister("export " + journal() + " --base " + (dir_ / "base.obj").string() +
                             " --glb --force --out " + (dir_ / "o2").string());
  EXPECT_EQ(journal_out.exit_code, 2) << journal_out.out;
  EXPECT_NE(journal_out.out.find("is a journal"), std::string::npos) << journal_out.out;
  // Not a journal; a zero up.
  std::ofstream(dir_ / "nope.twj") << "hello";
  EXPECT_EQ(
      host_test::run_twister("export " + (dir_ / "nope.twj").string() + " --base " +
                             (dir_ / "base.obj").string() + " --out " + (dir_ / "o3").string())
          .exit_code,
      2);
  const host_test::CommandRun zero =
      host_test::run_twister("export " + journal() + " --base " + (dir_ / "base.obj").string() +
                             " --up 0 0 0 --out " + (dir_ / "o4").string());
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.out.find("--up"), std::string::npos) << zero.out;
}

TEST_F(ExportCommand, LongJournalShowsProgress) {
  Station live(17);
  record(live, 400);
  ASSERT_GT(live.storage.bytes().size(), std::size_t{1} << 16);
  host_test::write_file(dir_ / "long.twj", live.storage.bytes());
  const host_test::CommandRun r = host_test::run_twister(
      "export " + (dir_ / "long.twj").string() + " --base " + (dir_ / "base.obj").string() +
      " --glb --out " + (dir_ / "long").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("twister export:  50% ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("replayed 400 records"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace twister
