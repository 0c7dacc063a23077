// twister-station as a process: simulator runs commit strokes to the journal, a
// simulated unplug/replug is survived, --check exit codes and messages, clean
// SIGTERM shutdown, sd_notify READY/WATCHDOG/STOPPING on a test socket.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "twister/hal/posix_file_storage.hpp"
#include "twister/journal/journal_reader.hpp"

namespace {

constexpr double kInch = 0.0254;

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout + stderr
};

// Runs a shell command line; exit_code is -1 when it could not start or did not exit.
RunResult run_command(const std::string& cmd) {
  RunResult r;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p) != nullptr) r.output += buf.data();
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

RunResult run(const std::string& args) {
  return run_command(std::string(TWISTER_STATION_BIN) + " " + args);
}

std::string temp_path(const char* name) {
  return "/tmp/twister_station_test_" + std::to_string(::getpid()) + "_" + name;
}

std::string write_file(const char* name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::vector<twister::journal::JournalRecord> read_journal(const std::string& path) {
  twister::hal::PosixFileStorage storage;
  EXPECT_TRUE(storage.open({.path = path, .create_if_missing = false}).ok());
  twister::journal::JournalReader reader(storage);
  EXPECT_TRUE(reader.open().ok());
  std::vector<twister::journal::JournalRecord> out;
  for (auto r = reader.next(); r.ok(); r = reader.next()) out.push_back(*r);
  EXPECT_EQ(reader.problem(), twister::journal::TailProblem::none);
  return out;
}

// [station] with this journal and the deploy folder's sphere.
std::string station_section(const std::string& journal) {
  return "[station]\njournal = \"" + journal + "\"\nmesh = \"" + TWISTER_DEPLOY_DIR +
         "/sim_sphere.obj\"\n";
}

std::string sim_config(const std::string& journal, const char* scenario, const char* time) {
  return station_section(journal) + "[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario = \"" +
         scenario + "\"\ntime = \"" + time + "\"\n[buttons]\nbackend = \"stylus\"\n";
}

TEST(TwisterStationTest, SimConfigRunsAScriptedStrokeIntoTheJournal) {
  const std::string journal = temp_path("sim.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const auto r = run(std::string("--config ") + TWISTER_DEPLOY_DIR +
                     "/sim.toml --log-level info --journal " + journal);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("stroke: hand 0 committed as journal record 0"), std::string::npos)
      << r.output;
  const auto records = read_journal(journal);
  ASSERT_EQ(records.size(), 1u);
  const auto& s = records[0].stroke;
  EXPECT_EQ(s.hand_mask, 1);
  // Scenario "stroke": receiver 1 pressed at (10, -8, 5) in, released at (14, -6, 5) in.
  EXPECT_NEAR(s.start[0].origin.x, 10.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.start[0].origin.y, -8.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.end[0].origin.x, 14.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.end[0].origin.y, -6.0 * kInch, 0.2 * kInch);

  // A second run replays the first stroke onto the model, then appends its own.
  const auto again =
      run(std::string("--config ") + TWISTER_DEPLOY_DIR + "/sim.toml --quiet --journal " + journal);
  EXPECT_EQ(again.exit_code, 0) << again.output;
  const auto both = read_journal(journal);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1].sequence, 1u);
  const std::string final_line = "twister-station: mesh checksum ";
  const auto at = again.output.rfind(final_line);
  ASSERT_NE(at, std::string::npos) << again.output;
  const std::string checksum = again.output.substr(at + final_line.size(), 16);
  // `twister replay` rebuilds the very same model from the journal and the OBJ.
  const auto replay = run_command(std::string(TWISTER_CLI_BIN) + " replay " + journal + " --mesh " +
                                  TWISTER_DEPLOY_DIR + "/sim_sphere.obj --out " + journal + ".obj");
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("checksum " + checksum), std::string::npos)
      << replay.output << again.output;
  ::unlink((journal + ".obj").c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

// [buttons] backend = "sim": the scenario's button lines press hand 0's and hand 1's
// grab together; the journal holds a single stroke made by both hands.
TEST(TwisterStationTest, SimButtonsLetBothHandsGrabTogetherIntoOneTwoHandStroke) {
  const std::string journal = temp_path("two_hands.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const std::string cfg =
      write_file("two_hands.toml", station_section(journal) +
                                       "[tracker]\nbackend = \"sim\"\n"
                                       "[tracker.sim]\nscenario_file = \"" TWISTER_SCENARIO_DIR
                                       "/sim_two_hands.scn\"\ntime = \"virtual\"\n"
                                       "[buttons]\nbackend = \"sim\"\n");
  const auto r = run("--config " + cfg);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("buttons sim (4 scripted events)"), std::string::npos) << r.output;
  const auto records = read_journal(journal);
  // Exactly one record: the two-hand stroke (both grabs end together in one commit).
  ASSERT_EQ(records.size(), 1u) << r.output;
  const auto& s = records[0].stroke;
  EXPECT_EQ(records[0].type, twister::journal::RecordType::stroke);
  EXPECT_EQ(s.hand_mask, 3) << r.output;
  EXPECT_EQ(s.chain_step, 0);
  // Hand 0 grabbed the -Y side and pulled to -Y; hand 1 the +Y side, pulled to +Y.
  EXPECT_NEAR(s.start[0].origin.y, -11.02 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.end[0].origin.y, -13.00 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.start[1].origin.y, -3.15 * kInch, 0.2 * kInch);
  EXPECT_NEAR(s.end[1].origin.y, -1.20 * kInch, 0.2 * kInch);
  // Twisted in opposite senses (roll +40 and -40 degrees about the tracker's x axis):
  // each hand's V axis left the x-y plane by sin(40 deg), on opposite sides.
  EXPECT_NEAR(s.start[0].v.z, 0.0, 0.02);
  EXPECT_NEAR(s.start[1].v.z, 0.0, 0.02);
  EXPECT_NEAR(std::abs(s.end[0].v.z), std::sin(40.0 * 3.14159265358979 / 180.0), 0.03);
  EXPECT_NEAR(s.end[1].v.z, -s.end[0].v.z, 0.03);
  ::unlink(cfg.c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

TEST(TwisterStationTest, UnplugAndReplugDuringARunReinitialisesAndContinues) {
  const std::string journal = temp_path("unplug.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const std::string cfg = write_file("unplug.toml", sim_config(journal, "unplug", "virtual"));
  const auto r = run("--config " + cfg + " --log-level info");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("tracker: lost"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("tracker: streaming (start-up #2)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stroke: hand 0 cancelled (tracking lost too long)"), std::string::npos)
      << r.output;
  const auto records = read_journal(journal);
  ASSERT_EQ(records.size(), 2u) << r.output;
  // Stroke 1 ends at (14, -6, 5) in; stroke 2 runs from there to (18, -4, 5) in.
  EXPECT_NEAR(records[0].stroke.end[0].origin.x, 14.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(records[1].stroke.start[0].origin.x, 14.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(records[1].stroke.start[0].origin.y, -6.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(records[1].stroke.end[0].origin.x, 18.0 * kInch, 0.2 * kInch);
  EXPECT_NEAR(records[1].stroke.end[0].origin.y, -4.0 * kInch, 0.2 * kInch);
  for (const auto& rec : records) {  // nothing from the untracked excursion to (30, 30, 30) in
    EXPECT_LT(rec.stroke.end[0].origin.x, 20.0 * kInch);
  }
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  ::unlink(cfg.c_str());
}

// twister-station against twister-sim on a PTY (real termios backend, real time).
// Starts twister-sim with a scenario and a symlink, waits for its first stdout line
// (the link is ready), runs the station for the scenario's length.
RunResult run_against_pty(const char* scenario, const std::string& journal, double seconds) {
  const std::string link = temp_path("fastrak.link");
  ::unlink(link.c_str());
  const std::string sim_cmd = std::string(TWISTER_SIM_BIN) + " --scenario " + TWISTER_SCENARIO_DIR +
                              "/" + scenario + " --reset-time 0.5 --link " + link;
  FILE* sim = ::popen(sim_cmd.c_str(), "r");
  RunResult r;
  if (sim == nullptr) return r;
  std::array<char, 256> line{};
  if (std::fgets(line.data(), line.size(), sim) == nullptr) {
    ::pclose(sim);
    return r;
  }
  const std::string cfg =
      write_file("pty.toml", station_section(journal) +
                                 "[tracker]\nbackend = \"serial\"\n"
                                 "reconnect_interval_ms = 200\n[tracker.serial]\ndevice = \"" +
                                 link +
                                 "\"\n"
                                 "[buttons]\nbackend = \"stylus\"\n[systemd]\nnotify = false\n");
  r = run("--config " + cfg + " --log-level info --duration " + std::to_string(seconds));
  ::pclose(sim);  // twister-sim stops at the end of its scenario
  ::unlink(cfg.c_str());
  ::unlink(link.c_str());
  return r;
}

TEST(TwisterStationTest, AgainstTwisterSimOnAPtyCommitsAScriptedStroke) {
  const std::string journal = temp_path("pty.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const auto r = run_against_pty("pty_stroke.txt", journal, 7.0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("tracker serial"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stroke: hand 0 committed as journal record 0"), std::string::npos)
      << r.output;
  const auto records = read_journal(journal);
  ASSERT_EQ(records.size(), 1u) << r.output;
  EXPECT_NEAR(records[0].stroke.start[0].origin.x, 10.0 * kInch, 0.3 * kInch);
  EXPECT_NEAR(records[0].stroke.end[0].origin.x, 14.0 * kInch, 0.3 * kInch);
  EXPECT_NEAR(records[0].stroke.end[0].origin.y, -6.0 * kInch, 0.3 * kInch);
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

// The PTY is closed mid-stroke and re-created at the same symlink 1.5 s later: the
// station reports, cancels the interrupted stroke, re-initialises the tracker and
// commits the next stroke; the journal holds exactly the two complete strokes.
TEST(TwisterStationTest, AgainstTwisterSimOnAPtySurvivesUnplugAndReplug) {
  const std::string journal = temp_path("pty_unplug.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const auto r = run_against_pty("pty_unplug.txt", journal, 15.5);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("tracker: lost"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stroke: hand 0 cancelled (tracking lost too long)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("tracker: streaming (start-up #2)"), std::string::npos) << r.output;
  const auto records = read_journal(journal);
  ASSERT_EQ(records.size(), 2u) << r.output;
  EXPECT_NEAR(records[0].stroke.end[0].origin.x, 14.0 * kInch, 0.3 * kInch);
  EXPECT_NEAR(records[1].stroke.start[0].origin.x, 14.0 * kInch, 0.3 * kInch);
  EXPECT_NEAR(records[1].stroke.end[0].origin.x, 18.0 * kInch, 0.3 * kInch);
  EXPECT_NEAR(records[1].stroke.end[0].origin.y, -4.0 * kInch, 0.3 * kInch);
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

TEST(TwisterStationTest, CheckAcceptsValidAndRefusesInvalidConfigs) {
  const auto ok = run(std::string("--config ") + TWISTER_DEPLOY_DIR + "/sim.toml --check");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("valid (tracker sim, buttons stylus)"), std::string::npos) << ok.output;

  const std::string bad = write_file(
      "bad.toml",
      "[station]\njournal = \"/nonexistent/dir/j.bin\"\nmesh = \"m.obj\"\nloop_timeout_ms = 0\n"
      "[tracker]\nbackend = \"sim\"\n[buttons]\nbackend = \"stylus\"\ncolour = \"red\"\n");
  const auto r = run("--config " + bad + " --check");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(
      r.output.find(bad + ":4: station.loop_timeout_ms: expected an integer from 1 to 1000, got 0"),
      std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(bad + ":9: buttons.colour: unknown key (allowed here: backend, "
                                "debounce_ms, gpiod, hidapi)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("2 error(s)"), std::string::npos) << r.output;
  // --check never opened the journal (its directory does not even exist).
  EXPECT_EQ(run("--config " + bad).exit_code, 2);

  const std::string no_stylus =
      write_file("nostylus.toml",
                 "[station]\njournal = \"/tmp/x\"\nmesh = \"m.obj\"\n[tracker]\nbackend = "
                 "\"sim\"\nleft_station = 2\n"
                 "right_station = 3\n[buttons]\nbackend = \"stylus\"\n");
  const auto ns = run("--config " + no_stylus + " --check");
  EXPECT_EQ(ns.exit_code, 2) << ns.output;
  EXPECT_NE(ns.output.find("needs receiver 1 (the stylus) in a hand"), std::string::npos)
      << ns.output;

  EXPECT_EQ(run("--config /nonexistent.toml --check").exit_code, 2);
  EXPECT_EQ(run("--check").exit_code, 2);  // --config is required
  EXPECT_EQ(run("--help").exit_code, 0);
  ::unlink(bad.c_str());
  ::unlink(no_stylus.c_str());
}

TEST(TwisterStationTest, NotAJournalIsRefusedAndLeftAlone) {
  const std::string journal = write_file("notjournal.bin", "precious data, not a journal\n");
  const std::string cfg = write_file("nj.toml", sim_config(journal, "idle", "virtual"));
  const auto r = run("--config " + cfg);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("is not a Twister journal, or does not fit this mesh (left untouched)"),
            std::string::npos)
      << r.output;
  std::ifstream in(journal);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), "precious data, not a journal\n");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  ::unlink(cfg.c_str());
}

// Real-time run under a fake systemd: READY=1, WATCHDOG=1 pings, SIGTERM -> STOPPING=1,
// exit 0 with the journal synced.
TEST(TwisterStationTest, SigtermStopsCleanlyAndSystemdIsNotified) {
  const std::string sock_path = temp_path("notify.sock");
  ::unlink(sock_path.c_str());
  const int sock = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", sock_path.c_str());
  ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  timeval tv{0, 200'000};
  ::setsockopt(sock, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);

  const std::string journal = temp_path("rt.bin");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const std::string cfg = write_file("rt.toml", sim_config(journal, "idle", "real") +
                                                    "[systemd]\nnotify = true\nwatchdog = true\n");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setenv("NOTIFY_SOCKET", sock_path.c_str(), 1);
    ::setenv("WATCHDOG_USEC", "200000", 1);
    ::unsetenv("WATCHDOG_PID");
    ::execl(TWISTER_STATION_BIN, TWISTER_STATION_BIN, "--config", cfg.c_str(), "--duration", "30",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::string messages;
  std::array<char, 256> buf{};
  for (int i = 0; i < 40 && messages.find("WATCHDOG=1") == std::string::npos; ++i) {
    const ssize_t n = ::recv(sock, buf.data(), buf.size() - 1, 0);
    if (n > 0) messages += std::string(buf.data(), static_cast<std::size_t>(n)) + "\n";
  }
  ::kill(pid, SIGTERM);
  for (int i = 0; i < 20 && messages.find("STOPPING=1") == std::string::npos; ++i) {
    const ssize_t n = ::recv(sock, buf.data(), buf.size() - 1, 0);
    if (n > 0) messages += std::string(buf.data(), static_cast<std::size_t>(n)) + "\n";
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_NE(messages.find("READY=1"), std::string::npos) << messages;
  EXPECT_NE(messages.find("WATCHDOG=1"), std::string::npos) << messages;
  EXPECT_NE(messages.find("STOPPING=1"), std::string::npos) << messages;
  EXPECT_TRUE(read_journal(journal).empty());  // idle: a valid, empty journal
  ::close(sock);
  ::unlink(sock_path.c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  ::unlink(cfg.c_str());
}

}  // namespace
