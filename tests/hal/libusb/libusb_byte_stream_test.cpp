// LibusbByteStream without a device: what a machine with no USB tracker (CI) can
// check here. Bulk traffic, enumeration by id, hot-plug and a unit without firmware:
// polhemus_usb_emulated_test (usbdevfs emulated with umockdev); claim conflicts and a
// real unit's timing need a rig (docs/hardware.md, "USB trackers").
#include "twister/hal/libusb_byte_stream.hpp"

#include <gtest/gtest.h>

#include <array>

namespace twister::hal {
namespace {

// Ids no real device uses, so a developer's machine gives the same answers as CI.
constexpr LibusbConfig kAbsent{.vendor_id = 0xfffe, .product_id = 0xfffd};

TEST(LibusbByteStreamTest, RejectsEndpointsWithTheWrongDirection) {
  LibusbByteStream in_is_out({.vendor_id = 1, .endpoint_in = 0x02, .endpoint_out = 0x01});
  EXPECT_EQ(in_is_out.init().code(), StatusCode::invalid_argument);
  LibusbByteStream out_is_in({.vendor_id = 1, .endpoint_in = 0x81, .endpoint_out = 0x82});
  EXPECT_EQ(out_is_in.init().code(), StatusCode::invalid_argument);
}

TEST(LibusbByteStreamTest, ReopenBeforeInitIsAPreconditionError) {
  LibusbByteStream stream(kAbsent);
  ports::ByteStream& port = stream;
  EXPECT_EQ(port.reopen().code(), StatusCode::failed_precondition);
}

TEST(LibusbByteStreamTest, AbsentDeviceIsUnavailableAndIoFailsUntilOpened) {
  LibusbByteStream stream(kAbsent);
  ASSERT_TRUE(stream.init().ok()) << "libusb error " << stream.last_error();
  ports::ByteStream& port = stream;
  EXPECT_EQ(port.reopen().code(), StatusCode::unavailable);  // not plugged in: retry later
  EXPECT_FALSE(stream.is_open());
  std::array<std::byte, 16> buf{};
  EXPECT_EQ(port.read(buf).status().code(), StatusCode::io_error);
  EXPECT_EQ(port.write(buf).status().code(), StatusCode::io_error);
  EXPECT_FALSE(stream.arrival_pending());
  port.discard_input();  // harmless while closed
}

TEST(LibusbByteStreamTest, InitTwiceIsHarmless) {
  LibusbByteStream stream(kAbsent);
  ASSERT_TRUE(stream.init().ok());
  EXPECT_TRUE(stream.init().ok());
  std::array<pollfd, 8> fds{};
  EXPECT_LE(stream.poll_fds(fds), fds.size());
}

// PollSource: nothing to wait on while the device is closed (nothing would handle
// libusb's events); reopen() is the ByteStream's.
TEST(LibusbByteStreamTest, PollSourceOffersNoDescriptorsWhileClosed) {
  LibusbByteStream stream(kAbsent);
  ASSERT_TRUE(stream.init().ok()) << "libusb error " << stream.last_error();
  PollSource& poll_source = stream;
  std::array<pollfd, 8> fds{};
  EXPECT_EQ(poll_source.poll_fds(fds), 0u);
  EXPECT_EQ(poll_source.reopen().code(), StatusCode::unavailable);
}

}  // namespace
}  // namespace twister::hal
