// StationLoop's own rules, in virtual time with the simulator tracker: failed
// buttons leave the poll set and are reopened through their PollSource every retry
// interval (logged); SIGTERM arrives through the signalfd and stops the loop; the
// run's length is counted from start().
#include "station_loop.hpp"

#include <gtest/gtest.h>
#include <signal.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "fakes/fake_storage.hpp"
#include "station_assembly.hpp"
#include "station_setup.hpp"

namespace twister::station_app {
namespace {

// A button device that can fail, counting how the loop uses it as a PollSource.
class FlakyButtons final : public ports::ButtonSource, public hal::PollSource {
 public:
  bool failing = false;
  bool reopen_works = false;
  StatusCode reopen_failure = StatusCode::unavailable;  // why a reopen fails
  mutable int poll_fds_calls = 0;
  int reopen_calls = 0;

 private:
  Result<ports::ButtonEdge> do_poll() override {
    if (!failing) return StatusCode::unavailable;
    connected_ = false;
    return StatusCode::io_error;
  }
  std::uint8_t do_line_count() const override { return 6; }
  bool do_connected() const override { return connected_; }
  std::size_t do_poll_fds(std::span<pollfd>) const override {
    ++poll_fds_calls;
    return 0;
  }
  Status do_reopen() override {
    ++reopen_calls;
    if (!reopen_works) return reopen_failure;
    failing = false;
    connected_ = true;
    return ok_status();
  }
  bool connected_ = true;
};

struct Rig {
  StationFileConfig config;
  Backends backends;
  FlakyButtons* buttons = nullptr;
  test::FakeStorage storage;
  std::unique_ptr<meshio::MeshBuffer> model;
  std::unique_ptr<WorkMemory> work;
  std::unique_ptr<station::Station> core;
  DisplayLink display;  // not opened
  std::FILE* log_file = std::tmpfile();
  hal::Logger log{{"twister-station", hal::LogLevel::info, false, ::fileno(log_file)}};

  Rig() {
    config.tracker.backend = TrackerBackend::sim;
    config.tracker.sim.scenario = "idle";
    config.tracker.sim.time = SimTime::virtual_time;
    config.tracker.reconnect_interval_ms = 500;
    config.buttons.backend = ButtonBackend::stylus;
    auto made = make_backends(config);
    EXPECT_TRUE(made) << made.error().message;
    backends = std::move(*made);
    auto flaky = std::make_unique<FlakyButtons>();
    buttons = flaky.get();
    backends.buttons_poll = flaky.get();
    backends.buttons = std::move(flaky);
    model = std::move(*load_station_mesh(TWISTER_DEPLOY_DIR "/sim_sphere.obj", 0));
    work = std::make_unique<WorkMemory>(model->mesh().vertex_capacity());
    core = std::make_unique<station::Station>(*backends.tracker, *backends.buttons, *backends.clock,
                                              storage, model->mesh(), work->storage(),
                                              *make_station_setup(config));
    EXPECT_TRUE(core->start().ok());
  }
  ~Rig() { std::fclose(log_file); }
  std::string log_text() {
    std::fflush(log_file);
    std::rewind(log_file);
    std::string text;
    for (int c = std::fgetc(log_file); c != EOF; c = std::fgetc(log_file)) {
      text += static_cast<char>(c);
    }
    return text;
  }
  StationLoopConfig loop_config(double seconds) {
    return make_loop_config(config, seconds, backends);
  }
};

TEST(StationLoop, FailedButtonsLeaveThePollSetAndAreReopenedEveryRetryInterval) {
  Rig rig;
  StationLoop loop(*rig.core, rig.backends, rig.display, rig.log, rig.loop_config(3.0));
  ASSERT_TRUE(loop.start());
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(loop.step());
  EXPECT_EQ(rig.buttons->poll_fds_calls, 100);  // asked once per pass
  rig.buttons->failing = true;
  ASSERT_TRUE(loop.step());  // the station reports the failure in this pass
  const int calls = rig.buttons->poll_fds_calls;
  for (int i = 0; i < 1200; ++i) ASSERT_TRUE(loop.step());  // 1.2 s: two retries (500 ms)
  EXPECT_EQ(rig.buttons->poll_fds_calls, calls);            // not waited on while broken
  EXPECT_EQ(rig.buttons->reopen_calls, 2);
  rig.buttons->reopen_works = true;
  for (int i = 0; i < 500; ++i) ASSERT_TRUE(loop.step());
  EXPECT_EQ(rig.buttons->reopen_calls, 3);
  EXPECT_GT(rig.buttons->poll_fds_calls, calls);  // back in the poll set
  while (loop.step()) {
  }
  EXPECT_EQ(loop.stop_reason(), StopReason::end_of_run);
  EXPECT_EQ(loop.passes(), 3000u);  // 3 s of 1 ms virtual steps
  const std::string log = rig.log_text();
  EXPECT_NE(log.find("twister-station: warning: buttons: device missing (io_error): running "
                     "without buttons"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("twister-station: buttons: device found: buttons work again"),
            std::string::npos)
      << log;
}

TEST(StationLoop, ADeviceThereButNotOpenableIsLoggedOnceNotEveryRetry) {
  Rig rig;
  StationLoop loop(*rig.core, rig.backends, rig.display, rig.log, rig.loop_config(7.0));
  ASSERT_TRUE(loop.start());
  rig.buttons->failing = true;  // unplugged
  for (int i = 0; i < 1200; ++i) ASSERT_TRUE(loop.step());
  rig.buttons->reopen_failure = StatusCode::invalid_argument;  // back, with a bad offset
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(loop.step());     // four retries
  rig.buttons->reopen_failure = StatusCode::unavailable;       // gone again
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(loop.step());
  rig.buttons->reopen_failure = StatusCode::io_error;  // back, busy
  for (int i = 0; i < 2000; ++i) ASSERT_TRUE(loop.step());
  EXPECT_EQ(rig.buttons->reopen_calls, 12);
  EXPECT_FALSE(rig.buttons->connected());
  const std::string log = rig.log_text();
  const std::string line = "twister-station: warning: buttons: device there but cannot be opened";
  auto at = log.find(line + " (invalid_argument); still running without buttons, retrying\n");
  EXPECT_NE(at, std::string::npos) << log;
  EXPECT_EQ(log.find(line + " (invalid_argument)", at + 1), std::string::npos) << log;
  at = log.find(line + " (io_error)");
  EXPECT_NE(at, std::string::npos) << log;
  EXPECT_EQ(log.find(line + " (io_error)", at + 1), std::string::npos) << log;
}

TEST(StationLoop, SigtermThroughTheSignalfdStopsTheLoop) {
  Rig rig;
  {
    StationLoop loop(*rig.core, rig.backends, rig.display, rig.log, rig.loop_config(0.0));
    ASSERT_TRUE(loop.start());
    ASSERT_TRUE(loop.step());
    ASSERT_EQ(::raise(SIGTERM), 0);  // blocked in this thread: pending on the signalfd
    EXPECT_FALSE(loop.step());
    EXPECT_EQ(loop.stop_reason(), StopReason::sigterm);
    EXPECT_STREQ(stop_reason_name(loop.stop_reason()), "SIGTERM");
    EXPECT_TRUE(loop.finish().ok());
  }
  sigset_t blocked;
  ASSERT_EQ(pthread_sigmask(SIG_BLOCK, nullptr, &blocked), 0);
  EXPECT_EQ(sigismember(&blocked, SIGTERM), 0);  // the loop restored the mask
}

}  // namespace
}  // namespace twister::station_app
