// Issue 21 item 4: start-up never blocks and a stop signal always ends it, releasing
// the journal's lock: a FIFO at the checkpoint (or journal) path, a Unix socket whose
// listener never accepts (full backlog), SIGTERM while start-up waits for a display.
// Every wait has a deadline that fails the test (a hung station is SIGKILLed).
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>

#include <chrono>
#include <cstring>
#include <filesystem>

#include "station_process.hpp"
#include "station_test_support.hpp"

namespace twister::station_test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class StartupIntegrity : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override {
    for (const int fd : sockets_) ::close(fd);
    fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string journal() const { return path("j.twj"); }
  std::string config() {
    write_file(path("still.scn"), still_scenario(60));
    write_file(path("station.toml"), station_config(journal(), TWISTER_DEPLOY_DIR "/sim_sphere.obj",
                                                    path("still.scn"), "real"));
    return path("station.toml");
  }
  // A listening Unix socket with backlog 0 whose queue is full: a blocking connect
  // to it waits until it accepts, which it never does.
  void full_backlog_socket(const std::string& at) {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, at.c_str(), sizeof addr.sun_path - 1);
    const int listener = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(listener, 0);
    sockets_.push_back(listener);
    ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    ASSERT_EQ(::listen(listener, 0), 0);
    int queued = 0;
    for (int i = 0; i < 8; ++i) {
      const int c = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK, 0);
      sockets_.push_back(c);
      if (::connect(c, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) ++queued;
    }
    ASSERT_GE(queued, 1);
  }
  // Starts the station, SIGTERMs it after `after_s` (if it still runs) and expects it
  // gone within 2 s of that with the lock released; returns its log.
  std::string start_then_terminate(const std::vector<std::string>& extra, double after_s,
                                   int& exit_code) {
    std::vector<std::string> argv = {TWISTER_STATION_BIN, "--config", config()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    BackgroundProcess station(argv, path("station.log"));
    station.wait_until([] { return false; }, after_s);
    const auto signalled = Clock::now();
    if (!station.exited()) ::kill(station.pid(), SIGTERM);
    exit_code = station.exit_within(2.0);
    EXPECT_NE(exit_code, -2) << "still running 2 s after SIGTERM:\n" << station.log();
    EXPECT_LT(Clock::now() - signalled, std::chrono::milliseconds(2100));
    if (fs::is_regular_file(journal())) {
      EXPECT_TRUE(journal_lock_is_free(journal()));
    }
    return station.log();
  }
  fs::path dir_ = fs::temp_directory_path() / ("startup_integrity_" + std::to_string(::getpid()));
  std::vector<int> sockets_;
};

TEST_F(StartupIntegrity, AFifoCheckpointIsRefusedWithoutBlockingAndTheLockReleased) {
  ASSERT_EQ(::mkfifo((journal() + ".ckpt").c_str(), 0600), 0);
  int rc = 0;
  const std::string log = start_then_terminate({}, 1.0, rc);
  EXPECT_EQ(rc, 1) << log;
  EXPECT_NE(log.find("is not a regular file"), std::string::npos) << log;
  struct stat st {};
  ASSERT_EQ(::lstat((journal() + ".ckpt").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));  // left as it was
}

TEST_F(StartupIntegrity, AFifoJournalIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo(journal().c_str(), 0600), 0);
  int rc = 0;
  const std::string log = start_then_terminate({}, 1.0, rc);
  EXPECT_EQ(rc, 2) << log;  // the config check, before anything is opened
  EXPECT_NE(log.find("is not a regular file"), std::string::npos) << log;
}

TEST_F(StartupIntegrity, AFullBacklogSocketIsRefusedWithoutBlockingAndTheLockReleased) {
  full_backlog_socket(path("busy.sock"));
  int rc = 0;
  const std::string log = start_then_terminate({"--link", "unix:" + path("busy.sock")}, 1.0, rc);
  EXPECT_EQ(rc, 1) << log;
  EXPECT_NE(log.find("listens on it"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(path("busy.sock")));  // the other program's socket stays
}

TEST_F(StartupIntegrity, SigtermWhileStartUpWaitsForADisplayEndsItWithinASecond) {
  std::vector<std::string> extra = {"--link", "unix:" + path("link.sock"), "--link-wait", "30"};
  int rc = 0;
  const auto started = Clock::now();
  const std::string log = start_then_terminate(extra, 1.5, rc);
  EXPECT_LT(Clock::now() - started, std::chrono::seconds(4)) << log;
  EXPECT_EQ(rc, 0) << log;  // the loop's first pass takes the signal: the normal stop
  EXPECT_NE(log.find("stopped (SIGTERM)"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(path("link.sock"))) << log;  // its socket removed at exit
}

TEST_F(StartupIntegrity, SigtermAtAnyMomentOfStartUpEndsItWithinTwoSeconds) {
  // Signals at several points of start-up (config, journal, model, link): every run
  // ends within 2 s of its signal and leaves the journal unlocked and readable.
  for (const double after : {0.0, 0.01, 0.03, 0.06, 0.1, 0.2}) {
    int rc = 0;
    const std::string log =
        start_then_terminate({"--link", "unix:" + path("l.sock"), "--link-wait", "30"}, after, rc);
    // 0: stopped by the loop; 1: start-up gave up; -1: the signal came before main.
    EXPECT_TRUE(rc == 0 || rc == 1 || rc == -1) << after << ": " << log;
    if (fs::exists(journal())) {
      EXPECT_TRUE(read_journal(journal()).opened || read_file(journal()).empty()) << log;
    }
  }
}

}  // namespace
}  // namespace twister::station_test
