// twister-station against damaged journals, full disks, a second station, signals and
// bad options (issue 11: items 1, 2, 3, 9), as a process with the in-process simulator.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "station_test_support.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_writer.hpp"

namespace twister::station_test {
namespace {

namespace fs = std::filesystem;

class StationIntegrity : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string config_for(const std::string& journal, int strokes, int freezes,
                         const char* time = "virtual") {
    const std::string scn = path("chains.scn");
    write_file(scn, chain_scenario(strokes, freezes));
    const std::string cfg = path("station.toml");
    write_file(cfg, sim_config(journal, scn, time));
    return cfg;
  }
  RunResult station(const std::string& args) {
    return run_command(std::string(TWISTER_STATION_BIN) + " " + args);
  }
  RunResult cli(const std::string& args) {
    return run_command(std::string(TWISTER_CLI_BIN) + " " + args);
  }
  // 20 one-hand strokes on the deploy sphere, written directly.
  void write_twenty_strokes(const std::string& journal) {
    hal::PosixFileStorage storage;
    ASSERT_TRUE(storage.open({.path = journal}).ok());
    journal::JournalWriter writer(storage);
    ASSERT_TRUE(writer.open().ok());
    for (std::uint32_t k = 0; k < 20; ++k) {
      journal::JournalRecord r;
      r.sequence = k;
      r.stroke.hand_mask = 1;
      r.stroke.radius_m = 0.06;
      r.stroke.start[0].origin = {0.30, -0.18, 0.15};
      r.stroke.end[0].origin = {0.30 + 0.002 * k, -0.18, 0.16};
      ASSERT_TRUE(writer.append(r).ok());
    }
  }
  fs::path dir_ = fs::temp_directory_path() / ("station_integrity_" + std::to_string(::getpid()));
};

// Salvage of a version 2 journal keeps the longest ordered valid prefix (issue 21): the
// four records before the damaged one; the 15 after it follow a missing sequence.
TEST_F(StationIntegrity, ABitFlipInRecord5Of20IsRefusedTheFileIsUntouchedAndSalvageKeeps4) {
  const std::string journal = path("j.twj");
  write_twenty_strokes(journal);
  std::string bytes = read_file(journal);
  constexpr std::size_t kHeader = journal::kMaxFileHeaderBytes;  // version 2
  const std::size_t record = (bytes.size() - kHeader) / 20;
  bytes[kHeader + 4 * record + 40] ^= 0x04;  // one bit in the 5th record's payload
  write_file(journal, bytes);
  const std::string cfg = config_for(journal, 1, 0);
  const RunResult r = station("--config " + cfg);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("damaged record at offset " + std::to_string(kHeader + 4 * record) +
                          " (bad_crc); 15 valid record(s) follow it"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(journal), bytes);  // byte-identical
  EXPECT_FALSE(fs::exists(journal + ".torn-tail"));
  // `twister replay` refuses too (exit 2), and salvage keeps the ordered prefix.
  EXPECT_EQ(cli("replay " + journal + " --mesh " TWISTER_DEPLOY_DIR "/sim_sphere.obj --out " +
                path("o.obj"))
                .exit_code,
            2);
  const RunResult check = cli("journal check " + journal);
  EXPECT_EQ(check.exit_code, 1);
  EXPECT_NE(check.output.find("verdict: corrupt"), std::string::npos) << check.output;
  const RunResult salvage = cli("journal salvage " + journal + " " + path("saved.twj") +
                                " --mesh " TWISTER_DEPLOY_DIR "/sim_sphere.obj");
  ASSERT_EQ(salvage.exit_code, 0) << salvage.output;
  EXPECT_NE(salvage.output.find("salvaged 4 of 19 valid records"), std::string::npos)
      << salvage.output;
  EXPECT_NE(salvage.output.find("15 after-a-gap record(s)"), std::string::npos) << salvage.output;
  const Journal saved = read_journal(path("saved.twj"));
  ASSERT_EQ(saved.records.size(), 4u);
  EXPECT_EQ(saved.records[3].sequence, 3u);
  EXPECT_EQ(read_file(journal), bytes);  // salvage only read it
  // The station starts from the salvaged copy.
  const RunResult again = station("--config " + cfg + " --journal " + path("saved.twj"));
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

TEST_F(StationIntegrity, ATornTailIsCutAndItsBytesAreKeptWithoutReplacingAnything) {
  const std::string journal = path("j.twj");
  write_twenty_strokes(journal);
  const std::string good = read_file(journal);
  // The start of a record, cut by power loss (after the version 2 header).
  const std::string torn = good.substr(journal::kMaxFileHeaderBytes, 60);
  write_file(journal, good + torn);
  write_file(journal + ".torn-tail", "an older tail, kept");
  const RunResult r = station("--config " + config_for(journal, 1, 0));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cut a torn tail of 60 bytes (torn_record) at offset " +
                          std::to_string(good.size()) + "; its bytes are kept in " + journal +
                          ".torn-tail.1"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(read_file(journal + ".torn-tail"), "an older tail, kept");
  EXPECT_EQ(read_file(journal + ".torn-tail.1"), torn);
  const Journal j = read_journal(journal);
  EXPECT_EQ(j.problem, journal::TailProblem::none);
  EXPECT_GE(j.records.size(), 20u);
}

TEST_F(StationIntegrity, ASecondStationOnTheSameJournalIsRefusedWithThePid) {
  const std::string journal = path("j.twj");
  const std::string cfg = config_for(journal, 1, 0, "real");
  const pid_t first = ::fork();
  ASSERT_GE(first, 0);
  if (first == 0) {
    FILE* quiet = std::freopen("/dev/null", "w", stderr);
    (void)quiet;
    ::execl(TWISTER_STATION_BIN, TWISTER_STATION_BIN, "--config", cfg.c_str(), "--duration", "20",
            "-q", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Wait until the first one holds the journal (it exists with its header).
  for (int i = 0; i < 200 && read_file(journal).size() < 8; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::string before = read_file(journal);
  const RunResult second = station("--config " + cfg + " --duration 1");
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find("is in use by another twister-station (PID " +
                               std::to_string(first) + ")"),
            std::string::npos)
      << second.output;
  EXPECT_EQ(read_file(journal), before);
  ::kill(first, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(first, &status, 0), first);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST_F(StationIntegrity, SighupAndSigtermDuringAStrokeCancelItCountItAndPrintTheSummary) {
  for (const int sig : {SIGHUP, SIGTERM}) {
    const std::string journal = path("sig" + std::to_string(sig) + ".twj");
    const std::string cfg = config_for(journal, 1, 3, "real");
    const std::string out = path("sig" + std::to_string(sig) + ".out");
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      FILE* f = std::freopen(out.c_str(), "w", stderr);
      (void)f;
      ::execl(TWISTER_STATION_BIN, TWISTER_STATION_BIN, "--config", cfg.c_str(), "--log-level",
              "info", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // The stroke starts at 3.05 s of the scenario; stop it half way.
    for (int i = 0; i < 400 && read_file(out).find("hand 1 grabbed") == std::string::npos; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(pid, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    const std::string log = read_file(out);
    ASSERT_TRUE(WIFEXITED(status)) << log;
    EXPECT_EQ(WEXITSTATUS(status), 0) << log;
    EXPECT_NE(log.find("hand 1 cancelled (station stopping); model unchanged"), std::string::npos)
        << log;
    EXPECT_NE(log.find(sig == SIGHUP ? "stopped (SIGHUP)" : "stopped (SIGTERM)"), std::string::npos)
        << log;
    // The freezes before the signal are committed; the open segment is not.
    const Journal j = read_journal(journal);
    EXPECT_EQ(j.records.size(), committed_sequences(log).size()) << log;
    EXPECT_NE(log.find("cancelled 1, not saved 0"), std::string::npos) << log;
  }
}

TEST_F(StationIntegrity, OptionAndFileErrorsExitTwoBeforeTheJournalIsTouched) {
  const std::string journal = path("j.twj");
  write_file(journal, "not a journal at all");  // replaying it would fail with exit 1
  const std::string cfg = config_for(journal, 1, 0);
  const RunResult link = station("--config " + cfg + " --link tcp:127.0.0.1:99999");
  EXPECT_EQ(link.exit_code, 2) << link.output;
  EXPECT_NE(
      link.output.find(
          "--link tcp:127.0.0.1:99999: expected tcp:A.B.C.D:PORT (IPv4 address, port 1..65535)"),
      std::string::npos)
      << link.output;
  EXPECT_EQ(station("--config " + cfg + " --link bogus").exit_code, 2);
  EXPECT_EQ(station("--config " + cfg + " --link unix:").exit_code, 2);
  // A config that is a device or too large is refused at once, never read forever.
  const RunResult zero = station("--config /dev/zero --check");
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("not a regular file"), std::string::npos) << zero.output;
  write_file(path("huge.toml"), std::string(2 << 20, '#'));
  EXPECT_EQ(station("--config " + path("huge.toml") + " --check").exit_code, 2);
  // --check verifies the files the config names.
  const std::string missing = path("missing.toml");
  write_file(missing, sim_config(journal, path("no_such.scn")));
  const RunResult check = station("--config " + missing + " --check");
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(
      check.output.find("tracker.sim.scenario_file: " + path("no_such.scn") + ": does not exist"),
      std::string::npos)
      << check.output;
  EXPECT_EQ(read_file(journal), "not a journal at all");
}

// RLIMIT_FSIZE is a real kernel limit (write(2) fails with EFBIG once the journal
// reaches it; the station ignores SIGXFSZ), so "disk full" here is the real thing.
RunResult run_with_file_limit(const std::string& cmd, rlim_t bytes) {
  return run_command("prlimit --fsize=" + std::to_string(bytes) + " " + cmd);
}

TEST_F(StationIntegrity, AFileSizeLimitMidChainLosesNoSavedStrokeAndRestartWorks) {
  const std::string full = path("full.twj");
  const std::string cfg = config_for(full, 8, 3);
  const RunResult whole = station("--config " + cfg + " --log-level info");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::size_t size = read_file(full).size();
  const Journal all = read_journal(full);
  ASSERT_EQ(all.records.size(), 32u) << whole.output;  // 8 strokes x (3 freezes + release)
  for (const std::size_t limit : {size / 3, size / 2 + 37, 3 * size / 4 + 101}) {
    SCOPED_TRACE(limit);
    const std::string journal = path("limit" + std::to_string(limit) + ".twj");
    const RunResult r = run_with_file_limit(std::string(TWISTER_STATION_BIN) + " --config " + cfg +
                                                " --journal " + journal + " --log-level info",
                                            limit);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("stroke not saved: file size limit reached"), std::string::npos)
        << r.output;
    const std::set<std::uint32_t> saved = committed_sequences(r.output);
    const Journal j = read_journal(journal);
    EXPECT_EQ(j.problem, journal::TailProblem::none);
    ASSERT_EQ(j.records.size(), saved.size()) << r.output;
    for (std::size_t i = 0; i < j.records.size(); ++i) {
      EXPECT_EQ(j.records[i].sequence, i);
      EXPECT_TRUE(saved.count(j.records[i].sequence) == 1);
      if (i > 0 && j.records[i].stroke.chain_step > 0) {  // chains never skip a step
        EXPECT_EQ(j.records[i].stroke.chain_step, j.records[i - 1].stroke.chain_step + 1);
      }
    }
    // Restart without the limit: it starts, and saves again after the last record.
    const RunResult again = station("--config " + cfg + " --journal " + journal + " -q");
    EXPECT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(cli("journal check " + journal).exit_code, 0);
  }
}

}  // namespace
}  // namespace twister::station_test
