// Issue 21 items 1 and 7: no tool writes over a running station's journal, its
// checkpoint or its base model; a base model changed under the station stops it
// before it writes anything; an empty checkpoint is replaced and a killed writer's
// temporaries are removed at the next start. twister-station, twister and
// twister-bridge as processes, the station on the in-process simulator.
#include <gtest/gtest.h>

#include <filesystem>

#include "station_process.hpp"
#include "station_test_support.hpp"

namespace twister::station_test {
namespace {

namespace fs = std::filesystem;

class WritersIntegrity : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_);
    fs::copy_file(TWISTER_DEPLOY_DIR "/sim_sphere.obj", base());
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string base() const { return path("base.obj"); }
  std::string journal() const { return path("j.twj"); }
  std::string checkpoint() const { return journal() + ".ckpt"; }
  // A config playing `scenario` on base.obj.
  std::string config(const std::string& scenario, const char* time) {
    write_file(path("run.scn"), scenario);
    write_file(path("station.toml"), station_config(journal(), base(), path("run.scn"), time));
    return path("station.toml");
  }
  // One stroke in virtual time to a clean stop: a journal and its checkpoint.
  void sculpt_once() {
    const RunResult r = run_command(std::string(TWISTER_STATION_BIN) + " --config " +
                                    config(chain_scenario(1, 0), "virtual") + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ASSERT_EQ(read_journal(journal()).records.size(), 1u) << r.output;
    ASSERT_EQ(read_file(checkpoint()).substr(0, 4), "TWCK") << r.output;
  }
  RunResult cli(const std::string& args) {
    return run_command(std::string(TWISTER_CLI_BIN) + " " + args);
  }
  fs::path dir_ = fs::temp_directory_path() / ("writers_integrity_" + std::to_string(::getpid()));
};

TEST_F(WritersIntegrity, ToolsRefuseTheLiveJournalItsCheckpointAndTheBaseModel) {
  sculpt_once();
  BackgroundProcess station({TWISTER_STATION_BIN, "--config", config(still_scenario(60), "real")},
                            path("station.log"));
  ASSERT_TRUE(station.wait_for_log("running", 10)) << station.log();
  const std::string journal_bytes = read_file(journal());
  const std::string checkpoint_bytes = read_file(checkpoint());
  const std::string base_bytes = read_file(base());
  const std::string deploy = TWISTER_DEPLOY_DIR "/sim_sphere.obj";
  struct Attempt {
    std::string args;
    std::string why;
  };
  const Attempt attempts[] = {
      {"replay " + journal() + " --mesh " + base() + " --out " + journal(), "is the input"},
      {"replay " + journal() + " --mesh " + base() + " --out " + journal() + " --force",
       "is the input"},
      {"replay " + journal() + " --mesh " + base() + " --out " + checkpoint() + " --force",
       "checkpoint"},
      {"replay " + journal() + " --mesh " + base() + " --out " + base() + " --force",
       "is the input"},
      {"replay " + journal() + " --mesh " + deploy + " --out " + base() + " --force", "in use"},
      {"replay " + journal() + " --mesh " + deploy + " --out " + base(), "in use"},
      {"mesh sphere --out " + base() + " --force", "in use"},
      {"mesh sphere --out " + journal() + " --force",
       "is in use (locked by PID " + std::to_string(station.pid())},
      {"mesh box --out " + checkpoint() + " --force", "checkpoint"},
  };
  for (const Attempt& a : attempts) {
    const RunResult r = cli(a.args);
    EXPECT_EQ(r.exit_code, 2) << a.args << "\n" << r.output;
    EXPECT_NE(r.output.find(a.why), std::string::npos) << a.args << "\n" << r.output;
  }
#ifdef TWISTER_BRIDGE_BIN
  // The display's export is checked at its start by the same rule.
  const RunResult exported =
      run_command(std::string(TWISTER_BRIDGE_BIN) + " --offscreen --size 64x48 --connect unix:" +
                  path("none.sock") + " --timeout 5 --force --export " + base());
  EXPECT_EQ(exported.exit_code, 2) << exported.output;
  EXPECT_NE(exported.output.find("in use"), std::string::npos) << exported.output;
#endif
  EXPECT_EQ(read_file(journal()), journal_bytes);
  EXPECT_EQ(read_file(checkpoint()), checkpoint_bytes);
  EXPECT_EQ(read_file(base()), base_bytes);
  // The station did not notice: it stops cleanly and starts again from its files.
  ::kill(station.pid(), SIGTERM);
  EXPECT_EQ(station.exit_within(5), 0) << station.log();
  EXPECT_NE(station.log().find("stopped (SIGTERM)"), std::string::npos) << station.log();
  const RunResult again = run_command(std::string(TWISTER_STATION_BIN) + " --config " +
                                      path("station.toml") + " --duration 0.2");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("restored the checkpoint of 1 records"), std::string::npos)
      << again.output;
  // Without a station the journal and checkpoint are still refused; an OBJ is
  // replaced only with --force.
  EXPECT_EQ(cli("mesh sphere --out " + journal() + " --force").exit_code, 2);
  EXPECT_EQ(cli("mesh sphere --out " + checkpoint() + " --force").exit_code, 2);
  EXPECT_EQ(cli("mesh sphere --out " + path("x.obj")).exit_code, 0);
  EXPECT_EQ(cli("mesh sphere --out " + path("x.obj")).exit_code, 2);
  EXPECT_EQ(cli("mesh sphere --out " + path("x.obj") + " --force").exit_code, 0);
  EXPECT_EQ(read_file(journal()), journal_bytes);
}

TEST_F(WritersIntegrity, ABaseModelChangedUnderTheStationStopsItBeforeItWritesAnything) {
  sculpt_once();
  // What `twister replay J --mesh BASE --out BASE` did before: the sculpted model
  // where the base was (here by a rename, as any other program might).
  const RunResult replayed =
      cli("replay " + journal() + " --mesh " + base() + " --out " + path("sculpted.obj"));
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  fs::rename(path("sculpted.obj"), base());
  const std::string journal_bytes = read_file(journal());
  const std::string checkpoint_bytes = read_file(checkpoint());
  const RunResult r = run_command(std::string(TWISTER_STATION_BIN) + " --config " +
                                  path("station.toml") + " --duration 1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("was made from another model than " + base()), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("refusing to start before anything is written"), std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(journal()), journal_bytes);
  EXPECT_EQ(read_file(checkpoint()), checkpoint_bytes);
  EXPECT_EQ(r.output.find("running"), std::string::npos) << r.output;
  // A damaged checkpoint proves nothing about the model: ignored, the journal replayed.
  std::string damaged = checkpoint_bytes;
  damaged[damaged.size() / 2] = static_cast<char>(damaged[damaged.size() / 2] ^ 0x40);
  write_file(checkpoint(), damaged);
  fs::copy_file(TWISTER_DEPLOY_DIR "/sim_sphere.obj", base(), fs::copy_options::overwrite_existing);
  const RunResult restored = run_command(std::string(TWISTER_STATION_BIN) + " --config " +
                                         path("station.toml") + " --duration 0.2");
  EXPECT_EQ(restored.exit_code, 0) << restored.output;
  EXPECT_NE(restored.output.find("ignored (damaged)"), std::string::npos) << restored.output;
}

TEST_F(WritersIntegrity, AnEmptyCheckpointIsReplacedAndAKilledWritersTemporariesRemoved) {
  write_file(checkpoint(), "");
  const char* ours[] = {"j.twj.ckpt.tmp-4242-0", "j.twj.ckpt.tmp-77-3", "j.twj.torn-tail.tmp-5-0"};
  const char* foreign[] = {"j.twj.ckpt.tmp-notes", "other.twj.ckpt.tmp-1-1", "j.twj.ckpt.bak"};
  for (const char* name : ours) write_file(path(name), "half a checkpoint");
  for (const char* name : foreign) write_file(path(name), "someone's file");
  const RunResult r = run_command(std::string(TWISTER_STATION_BIN) + " --config " +
                                  config(chain_scenario(1, 0), "virtual"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("removed 3 temporary file(s)"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(checkpoint()).substr(0, 4), "TWCK") << r.output;
  for (const char* name : ours) EXPECT_FALSE(fs::exists(path(name))) << name;
  for (const char* name : foreign) EXPECT_EQ(read_file(path(name)), "someone's file") << name;
}

#ifdef TWISTER_SIM_BIN
TEST_F(WritersIntegrity, TwisterSimLinksOnlyOverItsOwnSymbolicLink) {
  write_file(journal(), "a journal");
  const RunResult r = run_command(std::string(TWISTER_SIM_BIN) + " --reset-time 0.5 --link " +
                                  journal() + " --duration 0.2");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("is not a symbolic link; left untouched"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(journal()), "a journal");
}
#endif

}  // namespace
}  // namespace twister::station_test
