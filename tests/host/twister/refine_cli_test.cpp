// The CLI side of refinement (issue 13): `twister mesh box|cylinder|plane|sphere`
// writes closed (or, the plane, open) conforming meshes at the chosen resolution, and
// `twister replay` rebuilds a refined session's mesh bit for bit from its journal
// (given the station's spare capacity), and warns when that capacity was too small.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "cli_test_support.hpp"
#include "core/session/refine_harness.hpp"
#include "mesh_checks.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister {
namespace {

using namespace session::test_support;
namespace fs = std::filesystem;

TEST(RefineCli, MeshShapesAtAChosenResolution) {
  const host_test::ScratchDir dir("twister_refine_cli_shapes");
  struct Case {
    std::string args;
    std::size_t vertices;
    bool closed;
  };
  for (const Case& c : {Case{"box -n 3 --size 0.5", meshio::box_vertices(3), true},
                        Case{"box -n 12", meshio::box_vertices(12), true},
                        Case{"cylinder -n 4 --segments 16 --size 0.2 --half-height 0.5",
                             meshio::cylinder_vertices(4, 16), true},
                        Case{"sphere -n 10 --segments 20", meshio::sphere_vertices(10, 20), true},
                        Case{"plane -n 9 --size 0.5", 81, false}}) {
    const fs::path out = dir / "shape.obj";
    const auto r = host_test::run_twister("mesh " + c.args + " --out " + out.string() + " --force");
    ASSERT_EQ(r.exit_code, 0) << c.args << "\n" << r.out;
    const auto m = meshio::load_obj(out);
    ASSERT_TRUE(m) << m.error().message;
    EXPECT_EQ(m->buffer->mesh().vertex_count(), c.vertices) << c.args;
    if (c.closed) {
      EXPECT_TRUE(test_support::closed_manifold(m->buffer->mesh())) << c.args;
    }
  }
  EXPECT_EQ(host_test::run_twister("mesh box -n 1 --out " + (dir / "x.obj").string()).exit_code, 2);
  EXPECT_EQ(host_test::run_twister("mesh cone --out " + (dir / "x.obj").string()).exit_code, 2);
}

TEST(RefineCli, ReplayRebuildsARefinedSessionBitForBit) {
  const host_test::ScratchDir dir("twister_refine_cli_replay");
  RefineStation live(3, 6'000, refine_config(0.003));
  (void)twist_box(live, 170.0 * std::numbers::pi / 180.0);
  (void)twist_box(live, -1.0);
  ASSERT_TRUE(live.session->undo().ok());
  ASSERT_GT(live.mesh().vertex_count(), 26u);
  host_test::write_file(dir / "j.twj", live.storage.bytes());
  ASSERT_EQ(host_test::run_twister("mesh box -n 3 --size 0.5 --out " + (dir / "box.obj").string())
                .exit_code,
            0);
  const std::string replay = "replay " + (dir / "j.twj").string() + " --mesh " +
                             (dir / "box.obj").string() + " --out " + (dir / "out.obj").string() +
                             " --force";
  const auto same = host_test::run_twister(replay + " --spare-vertices 6000");
  ASSERT_EQ(same.exit_code, 0) << same.out;
  char checksum[32];
  std::snprintf(checksum, sizeof checksum, "checksum %016llx",
                static_cast<unsigned long long>(live.mesh().checksum()));
  EXPECT_NE(same.out.find(checksum), std::string::npos) << same.out;
  EXPECT_NE(same.out.find("refined 2 commits"), std::string::npos) << same.out;
  EXPECT_EQ(same.out.find("warning"), std::string::npos) << same.out;
  // Too little room: the strokes still apply, the refinement stops, and it says so.
  const auto small = host_test::run_twister(replay + " --spare-vertices 10");
  ASSERT_EQ(small.exit_code, 0) << small.out;
  EXPECT_NE(small.out.find("refinement stopped at this mesh's capacity in 2 commits"),
            std::string::npos)
      << small.out;
  EXPECT_EQ(small.out.find(checksum), std::string::npos) << small.out;
}

}  // namespace
}  // namespace twister
