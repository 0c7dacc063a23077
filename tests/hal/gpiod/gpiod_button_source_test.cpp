// GpiodButtonSource (unmodified, real libgpiod) against a fake GPIO chip: umockdev
// provides /dev/gpiochip0 and its sysfs entry and routes the chip's ioctls to the
// handler below, which answers CHIPINFO / LINEINFO and hands out the read end of a
// pipe as each line's event fd. The test writes kernel-format gpioevent_data records
// into the pipes. Not covered here (needs a rig, see docs/hardware.md): level reads,
// bias support of the kernel/driver, real edge timing and bounce.
#include "twister/hal/gpiod_button_source.hpp"

#include <gtest/gtest.h>
#include <linux/gpio.h>
#include <umockdev.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <mutex>
#include <vector>

// ASan builds: umockdev's LD_PRELOAD library loads before the ASan runtime, which
// ASan refuses by default; the order is harmless here. Unused in other builds.
extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::hal {
namespace {

constexpr std::uint32_t kChipLines = 32;

struct FakeChip {
  std::mutex mutex;
  std::vector<std::array<int, 2>> pipes;  // per requested line: [read, write]
  std::vector<std::uint32_t> requested_offsets;
  std::vector<std::uint32_t> requested_handle_flags;
  bool refuse_requests = false;
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
    if (info->line_offset >= kChipLines) {
      umockdev_ioctl_client_complete(client, -1, EINVAL);
      return TRUE;
    }
    info->flags = 0;
    std::snprintf(info->name, sizeof info->name, "line%u", info->line_offset);
  } else if (request == GPIO_GET_LINEEVENT_IOCTL) {
    UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpioevent_request), &error);
    auto* req = reinterpret_cast<gpioevent_request*>(d->data);
    std::lock_guard lock(chip->mutex);
    if (chip->refuse_requests) {
      umockdev_ioctl_client_complete(client, -1, EBUSY);
      return TRUE;
    }
    std::array<int, 2> p{};
    if (::pipe(p.data()) != 0) return FALSE;
    chip->pipes.push_back(p);
    chip->requested_offsets.push_back(req->lineoffset);
    chip->requested_handle_flags.push_back(req->handleflags);
    req->fd = p[0];  // same process: the backend reads events from this pipe
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

class GpiodButtonSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testbed_ = umockdev_testbed_new();
    // true only when the preload library is active and the testbed exists
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev-wrapper";
    GError* error = nullptr;
    // libgpiod compares sysfs "dev" with the node's major:minor after dropping the
    // last character, hence the literal \n.
    ASSERT_TRUE(umockdev_testbed_add_from_string(
        testbed_,
        "P: /devices/platform/gpio-sim.0/gpiochip0\nN: gpiochip0\nE: SUBSYSTEM=gpio\n"
        "E: DEVNAME=/dev/gpiochip0\nA: dev=254:0\\n\n",
        &error));
    handler_ = static_cast<UMockdevIoctlBase*>(g_object_new(UMOCKDEV_TYPE_IOCTL_BASE, nullptr));
    g_signal_connect(handler_, "handle-ioctl", G_CALLBACK(handle_ioctl), &chip_);
    ASSERT_TRUE(umockdev_testbed_attach_ioctl(testbed_, "/dev/gpiochip0", handler_, &error))
        << (error ? error->message : "");
  }
  void TearDown() override {
    source_.close();
    for (auto& p : chip_.pipes) ::close(p[1]);  // read ends were closed by libgpiod
    if (testbed_ != nullptr) g_object_unref(testbed_);
    if (handler_ != nullptr) g_object_unref(handler_);
  }
  void emit(std::size_t request_index, bool rising, std::int64_t sec, std::int64_t nsec) {
    gpioevent_data ev{};
    ev.timestamp = static_cast<__u64>(sec) * 1'000'000'000ull + static_cast<__u64>(nsec);
    ev.id = rising ? GPIOEVENT_EVENT_RISING_EDGE : GPIOEVENT_EVENT_FALLING_EDGE;
    ASSERT_EQ(::write(chip_.pipes.at(request_index)[1], &ev, sizeof ev),
              static_cast<ssize_t>(sizeof ev));
  }

  UMockdevTestbed* testbed_ = nullptr;
  UMockdevIoctlBase* handler_ = nullptr;
  FakeChip chip_;
  GpiodButtonSource source_;
};

TEST_F(GpiodButtonSourceTest, RequestsEachLineForEdgesActiveLow) {
  ASSERT_TRUE(source_.open({.chip = "gpiochip0", .lines = {17, 27}, .active_low = true}).ok())
      << "errno " << source_.last_errno();
  EXPECT_EQ(source_.line_count(), 2);
  ASSERT_EQ(chip_.requested_offsets, (std::vector<std::uint32_t>{17, 27}));
  for (auto flags : chip_.requested_handle_flags) {
    EXPECT_NE(flags & GPIOHANDLE_REQUEST_ACTIVE_LOW, 0u);
  }
  std::array<pollfd, 8> fds{};
  EXPECT_EQ(source_.poll_fds(fds), 2u);
}

// PollSource: the event fds while open; reopen() requests the same lines again.
TEST_F(GpiodButtonSourceTest, PollFdsAndReopenRequestTheConfiguredLines) {
  PollSource& poll_source = source_;
  std::array<pollfd, 8> fds{};
  EXPECT_EQ(poll_source.poll_fds(fds), 0u);
  EXPECT_EQ(poll_source.reopen().code(), StatusCode::failed_precondition);  // never opened
  ASSERT_TRUE(source_.open({.chip = "gpiochip0", .lines = {17, 27}}).ok());
  ASSERT_EQ(poll_source.poll_fds(fds), 2u);
  EXPECT_EQ(fds[0].events, POLLIN);
  EXPECT_NE(fds[0].fd, fds[1].fd);
  EXPECT_EQ(poll_source.poll_fds(std::span<pollfd>(fds.data(), 1)), 1u);  // no overrun
  ASSERT_TRUE(poll_source.reopen().ok());
  EXPECT_EQ(chip_.requested_offsets, (std::vector<std::uint32_t>{17, 27, 17, 27}));
  EXPECT_EQ(poll_source.poll_fds(fds), 2u);
}

TEST_F(GpiodButtonSourceTest, EdgesCarryLineLevelAndKernelTimestamp) {
  ASSERT_TRUE(source_.open({.chip = "gpiochip0", .lines = {17, 27}}).ok());
  ports::ButtonSource& port = source_;
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);  // nothing yet

  emit(1, /*rising=*/true, 12, 345'678'000);
  auto e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 1);
  EXPECT_TRUE(e->pressed);
  EXPECT_EQ(e->time_us, 12'345'678);

  emit(1, /*rising=*/false, 12, 400'000'000);
  e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 1);
  EXPECT_FALSE(e->pressed);
  EXPECT_EQ(e->time_us, 12'400'000);
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);
}

TEST_F(GpiodButtonSourceTest, BusyLineIsIoError) {
  chip_.refuse_requests = true;
  EXPECT_EQ(source_.open({.chip = "gpiochip0", .lines = {3}}).code(), StatusCode::io_error);
  EXPECT_EQ(source_.last_errno(), EBUSY);
}

TEST_F(GpiodButtonSourceTest, MissingChipIsUnavailable) {
  EXPECT_EQ(source_.open({.chip = "gpiochip7", .lines = {3}}).code(), StatusCode::unavailable);
}

TEST_F(GpiodButtonSourceTest, OffsetBeyondChipIsInvalidArgument) {
  EXPECT_EQ(source_.open({.chip = "gpiochip0", .lines = {40}}).code(),
            StatusCode::invalid_argument);
}

}  // namespace
}  // namespace twister::hal
