// `twister replay` end to end: a journal written by a live SculptSession is
// replayed by the CLI onto the same mesh (bit-identical checksum) and onto a finer
// one (same strokes), with progress output and clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_test_support.hpp"
#include "core/session/session_harness.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister {
namespace {

using namespace session::test_support;
namespace fs = std::filesystem;

class ReplayCommand : public ::testing::Test {
 protected:
  // A live session on the 17 x 17 grid (as the harness builds it): a few strokes.
  void record(Station& s, int strokes) {
    for (int k = 0; k < strokes; ++k) {
      const double x = -0.5 + 0.1 * (k % 10);
      s.hand(0, math::identity_frame({x, 0.1, 0}));
      s.button(kGrab0, true);
      (void)s.tick();
      s.hand(0, z_turn({x + 0.05, 0.15, 0.1}, 0.3));
      (void)s.tick();
      s.button(kGrab0, false);
      (void)s.tick();
    }
  }
  host_test::ScratchDir dir_{"twister_replay_test"};
};

TEST_F(ReplayCommand, SameMeshBitIdenticalAndFinerMeshSameStrokes) {
  Station live(17);
  record(live, 5);
  ASSERT_TRUE(live.session->undo().ok());
  host_test::write_file(dir_ / "j.twj", live.storage.bytes());
  // The harness grid is twister mesh grid -n 17 --size 1.
  ASSERT_TRUE(meshio::save_obj(dir_ / "coarse.obj", live.mesh).has_value());
  meshio::MeshBuffer initial(17 * 17, 2 * 16 * 16);
  make_grid(initial.mesh(), 17);
  ASSERT_TRUE(meshio::save_obj(dir_ / "initial.obj", initial.mesh()).has_value());
  ASSERT_EQ(host_test::run_twister("mesh grid -n 33 --size 1 --out " + (dir_ / "fine.obj").string())
                .exit_code,
            0);

  const host_test::CommandRun same = host_test::run_twister(
      "replay " + (dir_ / "j.twj").string() + " --mesh " + (dir_ / "initial.obj").string() +
      " --out " + (dir_ / "out.obj").string());
  ASSERT_EQ(same.exit_code, 0) << same.out;
  EXPECT_NE(same.out.find("replayed 6 records (strokes 5, moves 0, undos 1, redos 0)"),
            std::string::npos)
      << same.out;
  const auto out = meshio::load_obj(dir_ / "out.obj");
  ASSERT_TRUE(out) << out.error().message;
  EXPECT_EQ(out->buffer->mesh().checksum(), live.mesh.checksum());

  const host_test::CommandRun fine = host_test::run_twister(
      "replay " + (dir_ / "j.twj").string() + " --mesh " + (dir_ / "fine.obj").string() +
      " --out " + (dir_ / "fine_out.obj").string());
  ASSERT_EQ(fine.exit_code, 0) << fine.out;
  const auto f = meshio::load_obj(dir_ / "fine_out.obj");
  ASSERT_TRUE(f);
  for (std::uint32_t j = 0; j < 17; ++j) {
    for (std::uint32_t i = 0; i < 17; ++i) {
      const glm::vec3 c = live.mesh.position(j * 17 + i);
      const glm::vec3 p = f->buffer->mesh().position(2 * j * 33 + 2 * i);
      EXPECT_NEAR(c.x, p.x, 1e-5f);
      EXPECT_NEAR(c.y, p.y, 1e-5f);
      EXPECT_NEAR(c.z, p.z, 1e-5f);
    }
  }
}

TEST_F(ReplayCommand, LongJournalShowsProgressAndTornTailIsReported) {
  Station live(17);
  record(live, 400);
  const auto bytes = live.storage.bytes();
  ASSERT_GT(bytes.size(), std::size_t{1} << 16);
  host_test::write_file(dir_ / "long.twj", bytes.first(bytes.size() - 5));  // torn last record
  meshio::MeshBuffer initial(17 * 17, 2 * 16 * 16);
  make_grid(initial.mesh(), 17);
  ASSERT_TRUE(meshio::save_obj(dir_ / "initial.obj", initial.mesh()).has_value());
  const host_test::CommandRun r = host_test::run_twister(
      "replay " + (dir_ / "long.twj").string() + " --mesh " + (dir_ / "initial.obj").string() +
      " --out " + (dir_ / "out.obj").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("twister replay:  50% ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("torn_record tail"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("replayed 399 records"), std::string::npos) << r.out;
}

TEST_F(ReplayCommand, BadInputsExitTwo) {
  std::ofstream(dir_ / "not_a_journal") << "hello";
  std::ofstream(dir_ / "bad.obj") << "v 0 0 0\nf 1 2 3\n";
  meshio::MeshBuffer initial(9, 8);
  ASSERT_TRUE(meshio::make_grid(initial.mesh(), 3, 1.0f).ok());
  ASSERT_TRUE(meshio::save_obj(dir_ / "ok.obj", initial.mesh()).has_value());
  const host_test::CommandRun not_journal =
      host_test::run_twister("replay " + (dir_ / "not_a_journal").string() + " --mesh " +
                             (dir_ / "ok.obj").string() + " --out " + (dir_ / "o.obj").string());
  EXPECT_EQ(not_journal.exit_code, 2);
  EXPECT_NE(not_journal.out.find("not a Twister journal"), std::string::npos);
  const host_test::CommandRun bad_mesh =
      host_test::run_twister("replay " + (dir_ / "not_a_journal").string() + " --mesh " +
                             (dir_ / "bad.obj").string() + " --out " + (dir_ / "o.obj").string());
  EXPECT_EQ(bad_mesh.exit_code, 2);
  EXPECT_EQ(host_test::run_twister("replay").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "o.obj"));
}

}  // namespace
}  // namespace twister
