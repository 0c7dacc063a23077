// The `twister` CLI's stderr: lines are "twister <command>: message" (no level
// words), replay's -q drops progress but keeps warnings (a torn journal tail) and
// errors, and results stay on stdout.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_test_support.hpp"
#include "core/session/session_harness.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister {
namespace {

using namespace session::test_support;
namespace fs = std::filesystem;

// `twister ARGS`: stdout, and stderr in `err_file`.
struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class CliLog : public ::testing::Test {
 protected:
  CliRun run(const std::string& args) {
    const fs::path err = dir_ / "stderr.txt";
    const host_test::CommandRun r =
        host_test::run_command(std::string(TWISTER_CLI) + " " + args + " 2>" + err.string());
    return {r.exit_code, r.out, read_all(err)};
  }
  // A torn journal of a few strokes on the harness grid, and that grid as OBJ.
  void write_torn_journal() {
    Station live(17);
    for (int k = 0; k < 4; ++k) {
      live.hand(0, math::identity_frame({-0.5 + 0.1 * k, 0.1, 0}));
      live.button(kGrab0, true);
      (void)live.tick();
      live.hand(0, z_turn({-0.45 + 0.1 * k, 0.15, 0.1}, 0.3));
      (void)live.tick();
      live.button(kGrab0, false);
      (void)live.tick();
    }
    const auto bytes = live.storage.bytes();
    std::ofstream f(dir_ / "torn.twj", std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size() - 5));
    f.close();
    meshio::MeshBuffer grid(17 * 17, 2 * 16 * 16);
    make_grid(grid.mesh(), 17);
    ASSERT_TRUE(meshio::save_obj(dir_ / "grid.obj", grid.mesh()).has_value());
  }
  std::string replay_args() const {
    return "replay " + (dir_ / "torn.twj").string() + " --mesh " + (dir_ / "grid.obj").string() +
           " --out " + (dir_ / "out.obj").string() + " --progress";
  }
  host_test::ScratchDir dir_{"twister_cli_log_test"};
};

TEST_F(CliLog, ReplayShowsProgressAndTheTornTailByDefault) {
  write_torn_journal();
  const CliRun r = run(replay_args());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("twister replay: ", 0), 0u) << r.err;  // progress comes first
  EXPECT_NE(r.err.find("% (1 records)\n"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("twister replay: " + (dir_ / "torn.twj").string() + ": torn_record tail"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("warning:"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("replayed "), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("replayed "), std::string::npos) << r.err;
}

TEST_F(CliLog, QuietReplayKeepsWarningsAndDropsProgress) {
  write_torn_journal();
  const CliRun r = run(replay_args() + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('%'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("torn_record tail"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("replayed "), std::string::npos) << r.out;
}

TEST_F(CliLog, ErrorsNameTheCommandAndExitNonZero) {
  const CliRun missing = run("fastrak-dump --file " + (dir_ / "absent.bin").string());
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err,
            "twister fastrak-dump: cannot read " + (dir_ / "absent.bin").string() + "\n");
  const CliRun both = run("fastrak-dump -F -f --file -");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_EQ(both.err, "twister fastrak-dump: -F and -f exclude each other\n");
}

TEST_F(CliLog, CountersAreNoticesOnStderr) {
  std::ofstream(dir_ / "noise.bin") << "noise";
  const CliRun r = run("fastrak-dump --file " + (dir_ / "noise.bin").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("twister fastrak-dump: counters: bytes=5 "), std::string::npos) << r.err;
}

}  // namespace
}  // namespace twister
