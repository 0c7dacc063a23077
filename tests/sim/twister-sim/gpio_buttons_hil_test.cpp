// Issue 23, two-hand hardware in the loop without a rig: a two-hand scenario
// (box_twist.scn: both hands grab, counter-rotate, release) runs through the real
// programs as separate processes, with its buttons on emulated GPIO lines:
//
//   twister-sim --link PTY --buttons gpiod:gpiochip1:20,...,25  (the rig's machine A)
//        │ Fastrak records over a PTY         │ GPIO output lines 20..25 (libgpiod)
//        ▼                                    ▼  the "wire" (this process)
//   twister-station: [tracker] serial on the PTY, [buttons] gpiod gpiochip0 lines 5..10
//
// This process owns a umockdev testbed with two chips (tests/support/
// umockdev_gpio_chips.hpp); both programs run under umockdev's preload library, which
// forwards their GPIO ioctls to the handler here. The handler answers twister-sim's
// line-handle request and SET_LINE_VALUES ioctls and writes the resulting edges, as
// the kernel would report them on the station's active-low input lines, into the event
// pipes the station got for its lines (pipes made before it was spawned, so that it
// inherits their read ends). The final model checksum must equal the in-process run of
// the same scenario (run_scenario.py: the station's simulator backend in virtual time).
// Readiness, not sleeps: twister-sim starts once the station has requested its button
// lines; the station is stopped once twister-sim has played the whole scenario and the
// stroke is committed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/umockdev_gpio_chips.hpp"

extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }
extern char** environ;

namespace {

using namespace std::chrono_literals;

const std::string kBin = TWISTER_BIN_DIR;
const std::string kSource = TWISTER_SOURCE_DIR;
const std::string kScenario = kSource + "/sim/scenarios/box_twist.scn";
constexpr int kButtons = 6;                 // the paper's layout: 0-2 left, 3-5 right
constexpr std::uint32_t kSimFirst = 20;     // twister-sim drives gpiochip1 lines 20..25
constexpr std::uint32_t kStationFirst = 5;  // the station reads gpiochip0 lines 5..10

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string first_match(const std::string& text, const std::string& pattern) {
  std::smatch m;
  const std::regex re(pattern, std::regex::multiline);
  return std::regex_search(text, m, re) ? m[1].str() : "";
}

std::string last_match(const std::string& text, const std::string& pattern) {
  std::string last;
  const std::regex re(pattern, std::regex::multiline);
  for (std::sregex_iterator it(text.begin(), text.end(), re), end; it != end; ++it) {
    last = (*it)[1].str();
  }
  return last;
}

// Spawns argv with stdout and stderr into `log`; `clean`: without the preload library
// and the testbed (a run that must not see emulated devices). -1 on failure.
pid_t spawn(const std::vector<std::string>& args, const std::string& log, bool clean) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<std::string> env_text;
  // Sanitizer builds: the preload library comes before the ASan runtime in the
  // children too (harmless here, see __asan_default_options).
  std::string asan = "ASAN_OPTIONS=verify_asan_link_order=0";
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    if (clean && (entry.rfind("LD_PRELOAD=", 0) == 0 || entry.rfind("UMOCKDEV_DIR=", 0) == 0)) {
      continue;
    }
    if (entry.rfind("ASAN_OPTIONS=", 0) == 0) {
      asan = entry + ":verify_asan_link_order=0";
      continue;
    }
    env_text.push_back(entry);
  }
  env_text.push_back(asan);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

// Waits for the child's exit; its exit code, or -1 at the timeout (then it is killed).
int wait_exit(pid_t pid, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(20ms);
  }
}

// Waits until `log` contains `what` at least n times; false at the timeout.
bool wait_for_log(const std::string& log, const std::string& what, int n,
                  std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (count(read_file(log), what) < n) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(50ms);
  }
  return true;
}

// The scenario header's station settings (run_scenario.py reads the same lines).
std::string header_lines(const std::string& scenario, const std::string& tag) {
  std::string out;
  std::ifstream in(scenario);
  const std::string prefix = "# @" + tag + " ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) out += line.substr(prefix.size()) + "\n";
  }
  return out;
}

std::string offsets(std::uint32_t first) {
  std::string s;
  for (int i = 0; i < kButtons; ++i) {
    if (i > 0) s += ',';
    s += std::to_string(first + static_cast<std::uint32_t>(i));
  }
  return s;
}

class GpioButtonsHil : public ::testing::Test {
 protected:
  void SetUp() override {
    ::mkdir(out_.c_str(), 0755);
    ::unlink(link_.c_str());
  }
  void TearDown() override {
    for (const pid_t pid : {sim_, station_}) {
      if (pid > 0 && ::kill(pid, 0) == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
      }
    }
  }

  // The in-process run of the scenario (no emulated devices): its checksum.
  std::string reference() {
    const std::string log = out_ + "/reference.log";
    const pid_t pid = spawn({"/usr/bin/env", "python3", kSource + "/sim/scenarios/run_scenario.py",
                             kScenario, "--bin", kBin, "--out", out_ + "/reference"},
                            log, /*clean=*/true);
    EXPECT_GT(pid, 0);
    EXPECT_EQ(wait_exit(pid, 120s), 0) << read_file(log);
    return first_match(read_file(log), R"(^station ([0-9a-f]{16})$)");
  }

  std::string write_station_config() {
    const std::string path = out_ + "/station.toml";
    std::ofstream(path) << "[station]\njournal = \"" << out_ << "/journal.twj\"\nmesh = \"" << out_
                        << "/reference/start.obj\"\n"
                        << header_lines(kScenario, "station")
                        << "[tracker]\nbackend = \"serial\"\nleft_station = 1\nright_station = 2\n"
                           "reconnect_interval_ms = 200\n[tracker.serial]\ndevice = \""
                        << link_
                        << "\"\n[buttons]\nbackend = \"gpiod\"\ndebounce_ms = 10\n"
                           "[buttons.gpiod]\nchip = \"gpiochip0\"\nlines = ["
                        << offsets(kStationFirst)
                        << "]\nactive_low = true\nbias = \"pull-up\"\n"
                           "[systemd]\nnotify = false\nwatchdog = false\n[sculpt]\n"
                        << header_lines(kScenario, "sculpt") << header_lines(kScenario, "toml");
    return path;
  }

  const std::string out_ = TWISTER_TEST_OUT;
  const std::string link_ = out_ + "/fastrak";
  pid_t sim_ = -1;
  pid_t station_ = -1;
};

// One run of the chain: testbed, station, twister-sim; what the test checks.
struct ChainRun {
  bool complete = false;  // ran to the end
  std::string station_log, sim_log;
  twister::test::UmockdevGpioChips::Chip out_chip;
  std::uint64_t wire_edges = 0;
};

class GpioButtonsChain : public GpioButtonsHil {
 protected:
  // Runs the chain once. twister-sim's scenario clock starts when the station asks for
  // continuous output (--scenario-clock stream), as it does in the in-process run: the
  // station's start-up (about 2 s) never races the scenario's first press.
  void run_chain(ChainRun& run) {
    twister::test::UmockdevGpioChips chips;  // from here on, children see the emulated chips
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev's preload library";
    std::string error;
    ASSERT_TRUE(chips.add_chip("gpiochip0", 0, error)) << error;  // the station's inputs
    ASSERT_TRUE(chips.add_chip("gpiochip1", 1, error)) << error;  // twister-sim's outputs
    for (std::uint32_t i = 0; i < kButtons; ++i) {
      chips.connect("gpiochip1", kSimFirst + i, "gpiochip0", kStationFirst + i);
    }
    ::unlink((out_ + "/journal.twj").c_str());
    ::unlink((out_ + "/journal.twj.ckpt").c_str());

    // The station first: it requests its button lines (the event pipes it inherits) and
    // looks for the tracker on the link until twister-sim makes it.
    chips.pre_make_event_pipes(4 * kButtons);
    const std::string station_log = out_ + "/station.log";
    station_ = spawn({kBin + "/twister-station", "--config", write_station_config(), "--log-level",
                      "info", "--link", "unix:" + out_ + "/link.sock"},
                     station_log, /*clean=*/false);
    ASSERT_GT(station_, 0);
    ASSERT_TRUE(chips.wait_for_event_requests("gpiochip0", kButtons, 30s))
        << read_file(station_log);

    chips.set_output_client(-1);  // twister-sim's line handle: its own chip descriptor
    const std::string sim_log = out_ + "/sim.log";
    sim_ = spawn({kBin + "/twister-sim", "--scenario", kScenario, "--link", link_, "--reset-time",
                  "0.5", "--scenario-clock", "stream", "--command-time", "all=0", "--buttons",
                  "gpiod:gpiochip1:" + offsets(kSimFirst), "--log-level", "info"},
                 sim_log, /*clean=*/false);
    ASSERT_GT(sim_, 0);
    chips.set_output_client(sim_);
    ASSERT_TRUE(wait_for_log(station_log, "tracker: streaming", 1, 30s)) << read_file(station_log);

    // twister-sim ends at the scenario's end; the stroke is committed by then.
    EXPECT_EQ(wait_exit(sim_, 60s), 0) << read_file(sim_log);
    sim_ = -1;
    EXPECT_TRUE(wait_for_log(station_log, "committed as journal record", 1, 30s))
        << read_file(station_log);
    ::kill(station_, SIGTERM);
    EXPECT_EQ(wait_exit(station_, 60s), 0) << read_file(station_log);
    station_ = -1;
    run.complete = true;
    run.station_log = read_file(station_log);
    run.sim_log = read_file(sim_log);
    run.out_chip = chips.chip("gpiochip1");
    run.wire_edges = chips.wire_edges();
  }
};

TEST_F(GpioButtonsChain, TwoHandScenarioWithButtonsOnGpioMatchesTheInProcessRun) {
  const std::string expected = reference();
  ASSERT_EQ(expected.size(), 16u) << "no reference checksum";

  ChainRun run;
  run_chain(run);
  if (HasFatalFailure()) return;
  ASSERT_TRUE(run.complete);

  const std::string& slog = run.station_log;
  const std::string& simlog = run.sim_log;
  // The buttons came over the wire: four edges (both grabs pressed and released).
  ASSERT_EQ(run.out_chip.handles.size(), 1u) << simlog;
  EXPECT_NE(run.out_chip.handles[0].flags & GPIOHANDLE_REQUEST_OUTPUT, 0u);
  EXPECT_NE(run.out_chip.handles[0].flags & GPIOHANDLE_REQUEST_ACTIVE_LOW, 0u);
  EXPECT_EQ(run.out_chip.handles[0].consumer, "twister-sim");
  // Both presses in one write, both releases in one, and all released at exit.
  EXPECT_EQ(run.out_chip.value_writes.size(), 3u);
  EXPECT_EQ(run.wire_edges, 4u);
  EXPECT_NE(simlog.find("buttons: edges=4 not_played=0"), std::string::npos) << simlog;
  EXPECT_NE(slog.find("buttons gpiod gpiochip0"), std::string::npos) << slog;
  EXPECT_EQ(count(slog, "hand 0 grabbed"), 1) << slog;
  EXPECT_EQ(count(slog, "hand 1 grabbed"), 1) << slog;
  EXPECT_EQ(first_match(slog, R"(conversion errors (\d+))"), "0") << slog;
  // The model: equal to the in-process run of the same scenario.
  const std::string got = last_match(slog, R"(^twister-station: mesh checksum ([0-9a-f]+)$)");
  EXPECT_EQ(got, expected) << slog;
  std::printf("reference %s, station over PTY + emulated GPIO %s\n", expected.c_str(), got.c_str());
}

// twister-sim as a program: a missing chip, a busy line and an offset beyond the chip
// each end it with exit code 1 and a line saying which, before it serves anything.
TEST_F(GpioButtonsHil, TwisterSimSaysWhyItCannotHaveTheLines) {
  twister::test::UmockdevGpioChips chips;
  ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev's preload library";
  std::string error;
  ASSERT_TRUE(chips.add_chip("gpiochip1", 1, error)) << error;
  const std::string log = out_ + "/sim_errors.log";
  const auto sim = [&](const std::string& spec) {
    chips.set_output_client(-1);
    const pid_t pid =
        spawn({kBin + "/twister-sim", "--scenario", kScenario, "--link", link_, "--buttons", spec},
              log, /*clean=*/false);
    EXPECT_GT(pid, 0);
    chips.set_output_client(pid);
    const int rc = wait_exit(pid, 30s);
    chips.set_output_client(-1);
    return rc;
  };
  EXPECT_EQ(sim("gpiod:gpiochip7:20,21,22,23"), 1);
  EXPECT_NE(read_file(log).find("buttons: no GPIO chip gpiochip7"), std::string::npos)
      << read_file(log);
  EXPECT_EQ(sim("gpiod:gpiochip1:20,21,22,40"), 1);
  EXPECT_NE(read_file(log).find("gpiochip1 has no such line"), std::string::npos) << read_file(log);
  chips.refuse_requests("gpiochip1", true);
  EXPECT_EQ(sim("gpiod:gpiochip1:20,21,22,23"), 1);
  EXPECT_NE(read_file(log).find("cannot request the lines on gpiochip1: Device or resource "
                                "busy (errno 16); another program or driver holds a line"),
            std::string::npos)
      << read_file(log);
  EXPECT_EQ(sim("gpiod:gpiochip1:20,21,22"), 2);  // box_twist presses line 3: not wired
  EXPECT_NE(read_file(log).find("presses button line 3 but --buttons wires 3 lines"),
            std::string::npos)
      << read_file(log);
  struct stat st {};
  EXPECT_NE(::lstat(link_.c_str(), &st), 0) << "no PTY link is made";
}

}  // namespace
