// Issue 23: buttons that come and go, at the kernel interface. The station's REAL
// loop and backends (make_backends: the unmodified libgpiod backend, the simulator
// tracker in virtual time) with the GPIO chip emulated by umockdev (as in
// gpiod_button_source_test: sysfs entry, /dev node, an ioctl handler that hands out
// pipes as the lines' event fds). The chip is missing at start-up: the station runs,
// logs it once and reports it in its status (what the display's banner shows); the
// chip is added to the testbed while the loop runs and is picked up at the next
// retry; a grab on it starts a stroke; the chip is removed from the testbed in the
// middle of the stroke (its event fds hang up) and the stroke ends as on lost
// tracking; added again, it is picked up again. No exit anywhere.
#include <gtest/gtest.h>
#include <linux/gpio.h>
#include <umockdev.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fakes/fake_storage.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "station_setup.hpp"

extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::station_app {
namespace {

constexpr const char* kChipSysfs = "/sys/devices/platform/gpio-sim.0/gpiochip0";
constexpr std::uint32_t kChipLines = 32;

struct FakeChip {
  std::mutex mutex;
  std::vector<std::array<int, 2>> pipes;  // per requested line: [read, write]
  std::vector<std::uint32_t> offsets;
};

gboolean handle_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer user) {
  auto* chip = static_cast<FakeChip*>(user);
  const gulong request = umockdev_ioctl_client_get_request(client);
  UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
  GError* error = nullptr;
  if (request == GPIO_GET_CHIPINFO_IOCTL) {
    UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpiochip_info), &error);
    auto* info = reinterpret_cast<gpiochip_info*>(d->data);
    std::snprintf(info->name, sizeof info->name, "gpiochip0");
    std::snprintf(info->label, sizeof info->label, "twister-fake");
    info->lines = kChipLines;
  } else if (request == GPIO_GET_LINEINFO_IOCTL) {
    UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpioline_info), &error);
    auto* info = reinterpret_cast<gpioline_info*>(d->data);
    info->flags = 0;
    std::snprintf(info->name, sizeof info->name, "line%u", info->line_offset);
  } else if (request == GPIO_GET_LINEEVENT_IOCTL) {
    UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpioevent_request), &error);
    auto* req = reinterpret_cast<gpioevent_request*>(d->data);
    std::array<int, 2> p{};
    if (::pipe(p.data()) != 0) return FALSE;
    std::lock_guard lock(chip->mutex);
    chip->pipes.push_back(p);
    chip->offsets.push_back(req->lineoffset);
    req->fd = p[0];
  } else {
    umockdev_ioctl_client_complete(client, -1, ENOTTY);
    return TRUE;
  }
  if (error != nullptr) {
    g_error_free(error);
    return FALSE;
  }
  umockdev_ioctl_client_complete(client, 0, 0);
  return TRUE;
}

std::string temp_path(const char* name) {
  return "/tmp/twister_buttons_hotplug_" + std::to_string(::getpid()) + "_" + name;
}

class StationButtonsHotplug : public ::testing::Test {
 protected:
  void SetUp() override {
    testbed_ = umockdev_testbed_new();
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev-wrapper";
    handler_ = static_cast<UMockdevIoctlBase*>(g_object_new(UMOCKDEV_TYPE_IOCTL_BASE, nullptr));
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(handle_ioctl), &chip_);
    // Two still hands for 60 s (longer than the test runs).
    std::ofstream(scenario_) << "seed 1\nreceivers 2\nduration 60\n"
                                "key 0 1 10 -8 5 0 0 0\nkey 0 2 10 8 5 0 0 0\n";
    config_.tracker.backend = TrackerBackend::sim;
    config_.tracker.sim.scenario_file = scenario_;
    config_.tracker.sim.time = SimTime::virtual_time;
    config_.tracker.reconnect_interval_ms = 500;
    config_.buttons.backend = ButtonBackend::gpiod;
    config_.buttons.gpiod.chip = "gpiochip0";
    config_.buttons.gpiod.lines = {5, 6, 7, 8, 9, 10};  // button i = line 5 + i
  }
  void TearDown() override {
    loop_.reset();
    core_.reset();
    backends_ = {};
    close_pipes();
    if (testbed_ != nullptr) g_object_unref(testbed_);
    if (handler_ != nullptr) g_object_unref(handler_);
    std::fclose(log_file_);
    std::remove(scenario_.c_str());
  }

  // The node is a plain file (N: with contents), not umockdev's default pty: the
  // testbed keeps a pty node's master fd after remove_device() and refuses to
  // create that node again (an assertion in umockdev 0.17), so a pty chip could not
  // come back. A file node is an emulated char device too (major:minor from `dev`).
  void add_chip() {
    GError* error = nullptr;
    ASSERT_TRUE(umockdev_testbed_add_from_string(
        testbed_,
        "P: /devices/platform/gpio-sim.0/gpiochip0\nN: gpiochip0=00\nE: SUBSYSTEM=gpio\n"
        "E: DEVNAME=/dev/gpiochip0\nA: dev=254:0\\n\n",
        &error));
    ASSERT_TRUE(umockdev_testbed_attach_ioctl(testbed_, "/dev/gpiochip0", handler_, &error))
        << (error ? error->message : "");
  }
  // The chip goes: its node and sysfs entry leave the testbed, its lines' event fds
  // hang up (the writers close), as the kernel's do when a chip is removed.
  void remove_chip() {
    GError* error = nullptr;
    umockdev_testbed_detach_ioctl(testbed_, "/dev/gpiochip0", &error);
    umockdev_testbed_remove_device(testbed_, kChipSysfs);
    close_pipes();
  }
  void close_pipes() {
    std::lock_guard lock(chip_.mutex);
    for (auto& p : chip_.pipes) {
      if (p[1] >= 0) ::close(p[1]);
      p[1] = -1;
    }
  }
  // A level change of button `button` (its line's latest request), stamped now.
  void edge(std::size_t button, bool pressed) {
    std::lock_guard lock(chip_.mutex);
    const std::uint32_t offset = config_.buttons.gpiod.lines.at(button);
    for (std::size_t i = chip_.offsets.size(); i-- > 0;) {
      if (chip_.offsets[i] != offset) continue;
      gpioevent_data ev{};
      ev.timestamp = static_cast<__u64>(backends_.clock->now_us()) * 1000u;
      ev.id = pressed ? GPIOEVENT_EVENT_RISING_EDGE : GPIOEVENT_EVENT_FALLING_EDGE;
      ASSERT_EQ(::write(chip_.pipes[i][1], &ev, sizeof ev), static_cast<ssize_t>(sizeof ev));
      return;
    }
    FAIL() << "line " << offset << " was never requested";
  }

  void start() {
    auto made = make_backends(config_);
    ASSERT_TRUE(made) << made.error().message;  // a missing chip is no error
    backends_ = std::move(*made);
    model_ = std::move(*load_station_mesh(TWISTER_DEPLOY_DIR "/sim_sphere.obj", 0));
    work_ = std::make_unique<WorkMemory>(model_->mesh().vertex_capacity());
    core_ = std::make_unique<station::Station>(*backends_.tracker, *backends_.buttons,
                                               *backends_.clock, storage_, model_->mesh(),
                                               work_->storage(), *make_station_setup(config_));
    ASSERT_TRUE(core_->start().ok());
    loop_ = std::make_unique<StationLoop>(*core_, backends_, display_, log_,
                                          make_loop_config(config_, 60.0, backends_));
    ASSERT_TRUE(loop_->start());
  }
  // `ms` passes of 1 ms virtual time; every one must go on.
  void run_ms(int ms) {
    for (int i = 0; i < ms; ++i) ASSERT_TRUE(loop_->step()) << stop_reason_name(loop_->stop_reason());
  }
  std::string log_text() {
    std::fflush(log_file_);
    std::rewind(log_file_);
    std::string text;
    for (int c = std::fgetc(log_file_); c != EOF; c = std::fgetc(log_file_)) {
      text += static_cast<char>(c);
    }
    return text;
  }
  static int occurrences(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  }

  UMockdevTestbed* testbed_ = nullptr;
  UMockdevIoctlBase* handler_ = nullptr;
  FakeChip chip_;
  std::string scenario_ = temp_path("hands.scn");
  StationFileConfig config_;
  Backends backends_;
  test::FakeStorage storage_;
  std::unique_ptr<meshio::MeshBuffer> model_;
  std::unique_ptr<WorkMemory> work_;
  std::unique_ptr<station::Station> core_;
  DisplayLink display_;  // not opened
  std::FILE* log_file_ = std::tmpfile();
  hal::Logger log_{{"twister-station", hal::LogLevel::info, false, ::fileno(log_file_)}};
  std::unique_ptr<StationLoop> loop_;
};

TEST_F(StationButtonsHotplug, MissingAtBootPickedUpWhenAddedAndAStrokeEndsWhenRemoved) {
  start();  // no chip in the testbed
  EXPECT_EQ(backends_.buttons_name, "gpiod gpiochip0 (missing)");
  EXPECT_FALSE(backends_.buttons->connected());
  run_ms(1500);
  std::string log = log_text();
  EXPECT_EQ(occurrences(log, "buttons: device missing (unavailable)"), 1) << log;
  EXPECT_TRUE(core_->status().buttons_missing);

  add_chip();  // plugged in while the station runs
  run_ms(600);  // the next retry (every 500 ms) opens it
  ASSERT_TRUE(backends_.buttons->connected());
  log = log_text();
  EXPECT_EQ(occurrences(log, "buttons: device found"), 1) << log;
  EXPECT_FALSE(core_->status().buttons_missing);
  EXPECT_EQ(chip_.offsets.size(), 6u);

  edge(3, true);  // right grab (paper map: button 3)
  run_ms(50);
  ASSERT_EQ(occurrences(log_text(), "hand 1 grabbed"), 1) << log_text();

  remove_chip();  // unplugged mid-stroke
  run_ms(5);
  EXPECT_FALSE(backends_.buttons->connected());
  EXPECT_TRUE(core_->status().buttons_missing);
  run_ms(600);  // past the lost timeout (0.5 s)
  log = log_text();
  EXPECT_EQ(occurrences(log, "buttons: device missing (io_error)"), 1) << log;
  EXPECT_EQ(occurrences(log, "hand 1 lost tracking"), 1) << log;
  EXPECT_EQ(occurrences(log, "hand 1 cancelled (tracking lost too long)"), 1) << log;
  EXPECT_EQ(core_->counters().events.strokes_cancelled, 1u);
  EXPECT_EQ(core_->counters().events.strokes_committed, 0u);

  add_chip();  // and back
  run_ms(600);
  EXPECT_TRUE(backends_.buttons->connected());
  EXPECT_EQ(occurrences(log_text(), "buttons: device found"), 2) << log_text();
  EXPECT_EQ(chip_.offsets.size(), 12u);  // the lines requested again
  edge(3, true);
  run_ms(50);
  edge(3, false);
  run_ms(50);
  EXPECT_EQ(core_->counters().events.strokes_committed, 1u);
}

// A chip that appears but cannot give the configured lines (an offset beyond its 32
// lines) fails every retry: the station runs on without buttons, and says why once,
// not every interval.
TEST_F(StationButtonsHotplug, AChipWithABadOffsetIsLoggedOnceAndTheStationRunsOn) {
  config_.buttons.gpiod.lines = {5, 6, 7, 8, 9, 40};
  start();
  run_ms(600);
  add_chip();
  run_ms(2000);  // four retries, each refused by libgpiod (invalid_argument)
  EXPECT_FALSE(backends_.buttons->connected());
  EXPECT_TRUE(core_->status().buttons_missing);
  const std::string log = log_text();
  EXPECT_EQ(occurrences(log, "buttons: device missing (unavailable)"), 1) << log;
  EXPECT_EQ(occurrences(log, "buttons: device there but cannot be opened (invalid_argument)"), 1)
      << log;
  EXPECT_EQ(occurrences(log, "buttons: device found"), 0) << log;
}

}  // namespace
}  // namespace twister::station_app
