// GpiodLineOutput (unmodified, real libgpiod) against emulated GPIO chips: umockdev
// provides /dev/gpiochip0 and /dev/gpiochip1 and routes their ioctls to the handler of
// tests/support/umockdev_gpio_chips.hpp, which answers the line-handle request and
// records every SET_LINE_VALUES. A wire from gpiochip1 to gpiochip0 (as on a rig)
// shows the levels reaching an input line requested the way the station requests its
// buttons. Not covered here (needs a rig, docs/hil.md): real electrical levels, drive
// strength, open-drain behaviour of the chip, timing on a real kernel.
#include "twister/hal/gpiod_line_output.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "support/umockdev_gpio_chips.hpp"
#include "twister/hal/gpiod_button_source.hpp"

extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::hal {
namespace {

using Values = std::vector<std::uint8_t>;

class GpiodLineOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(umockdev_in_mock_environment()) << "run under umockdev-wrapper";
    std::string error;
    ASSERT_TRUE(chips_.add_chip("gpiochip0", 0, error)) << error;
    ASSERT_TRUE(chips_.add_chip("gpiochip1", 1, error)) << error;
  }
  void TearDown() override { output_.close(); }

  test::UmockdevGpioChips chips_;
  GpiodLineOutput output_;
};

TEST_F(GpiodLineOutputTest, RequestsAllLinesAsOneOutputHandleReleasedActiveLow) {
  ASSERT_TRUE(output_.open({.chip = "gpiochip1", .lines = {20, 23, 21}}).ok())
      << "errno " << output_.last_errno();
  EXPECT_EQ(output_.line_count(), 3u);
  const auto chip = chips_.chip("gpiochip1");
  ASSERT_EQ(chip.handles.size(), 1u);  // one request for all lines
  const auto& h = chip.handles[0];
  EXPECT_EQ(h.offsets, (std::vector<std::uint32_t>{20, 23, 21}));
  EXPECT_NE(h.flags & GPIOHANDLE_REQUEST_OUTPUT, 0u);
  EXPECT_NE(h.flags & GPIOHANDLE_REQUEST_ACTIVE_LOW, 0u);
  EXPECT_EQ(h.flags & (GPIOHANDLE_REQUEST_INPUT | GPIOHANDLE_REQUEST_OPEN_DRAIN), 0u);
  EXPECT_EQ(h.defaults, (Values{0, 0, 0}));  // every button released
  EXPECT_EQ(h.consumer, "twister-sim");
  // Released, active low: the lines rest high.
  EXPECT_TRUE(chip.physical.at(20));
  EXPECT_TRUE(chip.physical.at(23));
}

TEST_F(GpiodLineOutputTest, ActiveHighOpenDrainAndConsumer) {
  ASSERT_TRUE(output_
                  .open({.chip = "/dev/gpiochip1",
                         .lines = {4},
                         .active_low = false,
                         .open_drain = true,
                         .consumer = "rig"})
                  .ok());
  const auto h = chips_.chip("gpiochip1").handles.at(0);
  EXPECT_EQ(h.flags & GPIOHANDLE_REQUEST_ACTIVE_LOW, 0u);
  EXPECT_NE(h.flags & GPIOHANDLE_REQUEST_OPEN_DRAIN, 0u);
  EXPECT_EQ(h.consumer, "rig");
  EXPECT_FALSE(chips_.chip("gpiochip1").physical.at(4));  // released, active high: low
}

// Each set() writes every line's value (a v1 handle sets all its lines at once), so
// the other lines keep their levels; close() releases every line inactive.
TEST_F(GpiodLineOutputTest, SetWritesAllValuesAndCloseReleasesInactive) {
  ASSERT_TRUE(output_.open({.chip = "gpiochip1", .lines = {20, 21, 22}}).ok());
  ASSERT_TRUE(output_.set(1, true).ok()) << "errno " << output_.last_errno();
  ASSERT_TRUE(output_.set(2, true).ok());
  ASSERT_TRUE(output_.set(1, false).ok());
  EXPECT_TRUE(output_.active(2));
  EXPECT_FALSE(output_.active(1));
  auto chip = chips_.chip("gpiochip1");
  EXPECT_EQ(chip.value_writes, (std::vector<Values>{{0, 1, 0}, {0, 1, 1}, {0, 0, 1}}));
  EXPECT_FALSE(chip.physical.at(22));  // active low: pressed = low
  EXPECT_TRUE(chip.physical.at(21));
  output_.close();
  EXPECT_FALSE(output_.is_open());
  chip = chips_.chip("gpiochip1");
  EXPECT_EQ(chip.value_writes.back(), (Values{0, 0, 0}));
  EXPECT_TRUE(chip.physical.at(22));
}

// stage() changes lines without writing; flush() writes them in one ioctl (edges of
// one instant leave together), and nothing when nothing changed.
TEST_F(GpiodLineOutputTest, StagedLinesLeaveInOneWrite) {
  ASSERT_TRUE(output_.open({.chip = "gpiochip1", .lines = {20, 21, 22}}).ok());
  ASSERT_TRUE(output_.stage(0, true).ok());
  ASSERT_TRUE(output_.stage(2, true).ok());
  EXPECT_TRUE(chips_.chip("gpiochip1").value_writes.empty());
  ASSERT_TRUE(output_.flush().ok());
  ASSERT_TRUE(output_.flush().ok());         // nothing staged since
  ASSERT_TRUE(output_.stage(2, true).ok());  // no change
  ASSERT_TRUE(output_.flush().ok());
  EXPECT_EQ(chips_.chip("gpiochip1").value_writes, (std::vector<Values>{{1, 0, 1}}));
  EXPECT_EQ(output_.stage(3, true).code(), StatusCode::invalid_argument);
}

// Output wired to the station's input backend (GpiodButtonSource, active low on both
// ends): a set() arrives as the button's edge, pressed on press.
TEST_F(GpiodLineOutputTest, WiredToAButtonSourceAPressIsAPressedEdge) {
  chips_.connect("gpiochip1", 20, "gpiochip0", 5);
  chips_.connect("gpiochip1", 21, "gpiochip0", 6);
  GpiodButtonSource buttons;
  ASSERT_TRUE(buttons.open({.chip = "gpiochip0", .lines = {5, 6}, .active_low = true}).ok());
  ASSERT_TRUE(output_.open({.chip = "gpiochip1", .lines = {20, 21}}).ok());
  ports::ButtonSource& port = buttons;
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);  // released: no edge
  ASSERT_TRUE(output_.set(1, true).ok());
  auto e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->line, 1);
  EXPECT_TRUE(e->pressed);
  ASSERT_TRUE(output_.set(1, false).ok());
  e = port.poll();
  ASSERT_TRUE(e.ok());
  EXPECT_FALSE(e->pressed);
  EXPECT_EQ(port.poll().status().code(), StatusCode::unavailable);
  EXPECT_EQ(chips_.wire_edges(), 2u);
}

TEST_F(GpiodLineOutputTest, MissingChipIsUnavailable) {
  EXPECT_EQ(output_.open({.chip = "gpiochip7", .lines = {3}}).code(), StatusCode::unavailable);
  EXPECT_FALSE(output_.is_open());
}

TEST_F(GpiodLineOutputTest, BusyLineIsIoErrorWithErrno) {
  chips_.refuse_requests("gpiochip1", true);
  EXPECT_EQ(output_.open({.chip = "gpiochip1", .lines = {3}}).code(), StatusCode::io_error);
  EXPECT_EQ(output_.last_errno(), EBUSY);
  EXPECT_FALSE(output_.is_open());
}

TEST_F(GpiodLineOutputTest, BadLinesAreInvalidArgument) {
  EXPECT_EQ(output_.open({.chip = "gpiochip1", .lines = {40}}).code(),
            StatusCode::invalid_argument);  // beyond the chip's 32 lines
  EXPECT_EQ(output_.open({.chip = "gpiochip1", .lines = {}}).code(), StatusCode::invalid_argument);
  EXPECT_EQ(output_.open({.chip = "gpiochip1", .lines = {3, 3}}).code(),
            StatusCode::invalid_argument);
  EXPECT_TRUE(chips_.chip("gpiochip1").handles.empty());  // nothing was requested
}

TEST_F(GpiodLineOutputTest, SetNeedsAnOpenOutputAndAnExistingLine) {
  EXPECT_EQ(output_.set(0, true).code(), StatusCode::failed_precondition);
  ASSERT_TRUE(output_.open({.chip = "gpiochip1", .lines = {3}}).ok());
  EXPECT_EQ(output_.set(1, true).code(), StatusCode::invalid_argument);
  EXPECT_TRUE(chips_.chip("gpiochip1").value_writes.empty());
}

}  // namespace
}  // namespace twister::hal
