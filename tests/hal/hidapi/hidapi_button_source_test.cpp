// HidapiButtonSource (unmodified) over a fake hidapi linked in with --wrap: device
// lookup by ids or path, non-blocking reads of queued reports, edges stamped with the
// injected clock, unplug (hid_read < 0) and reopen. Real hidraw timing and permissions
// need a rig (docs/hardware.md).
#include "twister/hal/hidapi_button_source.hpp"

#include <gtest/gtest.h>
#include <hidapi/hidapi.h>

#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "fakes/fake_clock.hpp"

namespace {

struct FakeHid {
  bool present = true;
  std::string path = "/dev/hidraw7";
  std::deque<std::vector<unsigned char>> reports;
  bool unplugged = false;
  bool nonblocking = false;
  std::string opened_path;
  int opens = 0;
  int closes = 0;
  hid_device_info info{};
} g_hid;

hid_device* const kHandle = reinterpret_cast<hid_device*>(0x1);

}  // namespace

extern "C" {
int __wrap_hid_init() { return 0; }
hid_device_info* __wrap_hid_enumerate(unsigned short vid, unsigned short pid) {
  if (!g_hid.present || vid != 0x05f3 || pid != 0x00ff) return nullptr;
  g_hid.info = {};
  g_hid.info.path = g_hid.path.data();
  g_hid.info.vendor_id = vid;
  g_hid.info.product_id = pid;
  return &g_hid.info;
}
void __wrap_hid_free_enumeration(hid_device_info*) {}
hid_device* __wrap_hid_open_path(const char* path) {
  if (!g_hid.present || g_hid.path != path) return nullptr;
  g_hid.opened_path = path;
  g_hid.unplugged = false;
  ++g_hid.opens;
  return kHandle;
}
int __wrap_hid_set_nonblocking(hid_device*, int nonblock) {
  g_hid.nonblocking = nonblock != 0;
  return 0;
}
int __wrap_hid_read(hid_device*, unsigned char* data, size_t length) {
  if (g_hid.unplugged) return -1;
  if (g_hid.reports.empty()) return 0;  // non-blocking: nothing pending
  const auto r = g_hid.reports.front();
  g_hid.reports.pop_front();
  const size_t n = std::min(length, r.size());
  std::memcpy(data, r.data(), n);
  return static_cast<int>(n);
}
void __wrap_hid_close(hid_device*) { ++g_hid.closes; }
}

namespace twister::hal {
namespace {

class HidapiButtonSourceTest : public ::testing::Test {
 protected:
  void SetUp() override { g_hid = FakeHid{}; }
  HidapiButtonConfig pedal() const {
    HidapiButtonConfig c;
    c.vendor_id = 0x05f3;
    c.product_id = 0x00ff;
    c.buttons = {{1, 0x04}, {1, 0x08}};
    return c;
  }
  test::FakeClock clock_{5'000'000};
};

TEST_F(HidapiButtonSourceTest, OpensByIdsNonBlockingAndMapsReportsToEdges) {
  HidapiButtonSource source(clock_);
  ASSERT_TRUE(source.open(pedal()).ok());
  EXPECT_EQ(g_hid.opened_path, "/dev/hidraw7");
  EXPECT_TRUE(g_hid.nonblocking);
  ports::ButtonSource& port = source;
  EXPECT_EQ(port.line_count(), 2);
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);

  g_hid.reports.push_back({0x00, 0x04});         // left pedal down
  g_hid.reports.push_back({0x00, 0x04});         // repeat report: no edge
  g_hid.reports.push_back({0x00, 0x08 | 0x01});  // left up, right down (0x01 not mapped)
  clock_.advance_us(1'000);
  auto e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 0);
  EXPECT_TRUE(e->pressed);
  EXPECT_EQ(e->time_us, 5'001'000);
  e = port.poll();  // skips the unchanged report
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 0);
  EXPECT_FALSE(e->pressed);
  e = port.poll();  // second edge of the same report
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 1);
  EXPECT_TRUE(e->pressed);
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);
}

TEST_F(HidapiButtonSourceTest, PathWinsOverIds) {
  HidapiButtonSource source(clock_);
  auto c = pedal();
  c.vendor_id = 0x1234;  // would not enumerate
  c.path = "/dev/hidraw7";
  ASSERT_TRUE(source.open(c).ok());
  EXPECT_EQ(g_hid.opened_path, "/dev/hidraw7");
  c.path = "/dev/hidraw9";
  EXPECT_EQ(source.open(c).code(), StatusCode::unavailable);
}

TEST_F(HidapiButtonSourceTest, AbsentDeviceIsUnavailable) {
  g_hid.present = false;
  HidapiButtonSource source(clock_);
  EXPECT_EQ(source.open(pedal()).code(), StatusCode::unavailable);
}

TEST_F(HidapiButtonSourceTest, UnplugIsIoErrorAndReopenResumes) {
  HidapiButtonSource source(clock_);
  ASSERT_TRUE(source.open(pedal()).ok());
  g_hid.unplugged = true;
  ports::ButtonSource& port = source;
  EXPECT_EQ(port.poll().status().code(), StatusCode::io_error);
  ASSERT_TRUE(source.open(pedal()).ok());  // what the station loop does on io_error
  EXPECT_EQ(g_hid.opens, 2);
  EXPECT_EQ(g_hid.closes, 1);
  g_hid.reports.push_back({0x00, 0x08});
  auto e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 1);
}

TEST_F(HidapiButtonSourceTest, EmptyButtonMapIsRefused) {
  HidapiButtonSource source(clock_);
  auto c = pedal();
  c.buttons.clear();
  EXPECT_EQ(source.open(c).code(), StatusCode::invalid_argument);
  EXPECT_EQ(g_hid.opens, 0);
}

}  // namespace
}  // namespace twister::hal
