// Issue 22's acceptance: the emulated USB Liberty and the simulated serial Liberty give
// the same poses for the same motion (label devices).
//
// One scenario (two hands moving from t = 0, the stylus pressed from 3 s to 4 s) is
// played by the device model of `twister-sim --model liberty` twice:
//   (a) behind usbdevfs: the model answers the URBs of the station's USB backend (real
//       libusb under umockdev's preload, the model on the real clock), the station's
//       session set up for `backend = "usb"` with the model detected from the id;
//   (b) behind the serial interface: the model in process as the station's ByteStream
//       (SimFastrakStream, virtual time), the session set up for `backend = "serial"`,
//       `model = "liberty"`.
// Both units sample the motion at the same instants (the 120 Hz cycle from power-up), so
// the k-th cycle's pose is one value; the two sides start streaming at different
// cycles (different start-up pauses, real against virtual time). Every pose (a) received
// from the first one that (b) also received on must then be (b)'s next pose: station,
// position, quaternion and stylus equal as floats (tolerance 0: both decode the same
// float32 bytes, so any difference in units, frame, quaternion order or station is a
// failure, and the test shows it fails for inches against centimetres).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "fakes/fake_clock.hpp"
#include "hal/libusb/polhemus_usb_rig.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"

extern "C" const char* __asan_default_options() { return "verify_asan_link_order=0"; }

namespace twister::station_app {
namespace {

using namespace usbtest;  // NOLINT(google-build-using-namespace): the rig's names
using tracker::FastrakPose;

// Both hands move all the time (so every cycle's pose differs from every other's).
constexpr const char* kMotion =
    "receivers 2\nseed 3\n"
    "key 0 1 10 0 0 0 0 0\nkey 3 1 13 -1.5 0.75 6 3 1.5 1\nkey 4 1 14 -2 1 8 4 2\n"
    "key 20 1 30 -10 5 40 20 10\n"
    "key 0 2 15 5 0 0 0 0\nkey 20 2 19 9 -3 -60 10 5\n";

sim::Scenario motion() {
  sim::Scenario sc;
  std::string err;
  EXPECT_TRUE(sim::parse_scenario(kMotion, sc, err)) << err;
  return sc;
}

sim::FastrakDeviceConfig liberty_unit() {
  sim::FastrakDeviceConfig d;
  d.model = sim::DeviceModel::liberty;
  d.reset_time_us = 100'000;  // a quick boot, as tests pass --reset-time
  return d;
}

bool same_pose(const FastrakPose& a, const FastrakPose& b) {
  return a.station == b.station && a.position == b.position && a.quaternion == b.quaternion &&
         a.button == b.button;
}

// How `usb` lines up with `serial`: the USB poses before the first one the serial side
// has too (the serial side started later), then every USB pose against the serial
// side's next one.
struct Alignment {
  std::size_t before_overlap = 0;  // USB poses before the first shared one
  std::size_t compared = 0;        // USB poses compared from there on
  std::size_t unequal = 0;         // of those, not the serial side's next pose
  std::string first_difference;
};

Alignment align(const std::vector<FastrakPose>& usb, const std::vector<FastrakPose>& serial) {
  Alignment a;
  std::size_t j = serial.size();
  for (; a.before_overlap < usb.size(); ++a.before_overlap) {
    for (j = 0; j < serial.size() && !same_pose(serial[j], usb[a.before_overlap]); ++j) {
    }
    if (j < serial.size()) break;
  }
  for (std::size_t i = a.before_overlap; i < usb.size() && j < serial.size(); ++i, ++j) {
    ++a.compared;
    if (same_pose(usb[i], serial[j])) continue;
    if (a.unequal++ == 0) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "USB pose %zu: station %d (%g, %g, %g); serial: station %d (%g, %g, %g)", i,
                    usb[i].station, usb[i].position[0], usb[i].position[1], usb[i].position[2],
                    serial[j].station, serial[j].position[0], serial[j].position[1],
                    serial[j].position[2]);
      a.first_difference = text;
    }
  }
  return a;
}

// The station's session for a serial Liberty (the serial backend's own timings).
tracker::FastrakSessionConfig serial_session() {
  const std::string text =
      "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = "
      "\"serial\"\nmodel = \"liberty\"\n[tracker.serial]\ndevice = \"/dev/ttyUSB0\"\n"
      "[buttons]\nbackend = \"stylus\"\n";
  const ConfigParseResult parsed = parse_station_config(text, "serial.toml");
  EXPECT_TRUE(parsed.ok()) << parsed.errors.front().to_string();
  auto setup = make_station_setup(parsed.config);
  EXPECT_TRUE(setup) << setup.error().message;
  return setup->session;
}

// (b): the serial Liberty in virtual time, `seconds` of it, the station starting it
// `delay_us` after its power-up.
std::vector<FastrakPose> serial_poses(double seconds, std::int64_t delay_us) {
  test::FakeClock clock{0};
  sim::SimFastrakStream stream(clock, liberty_unit(), motion());
  clock.advance_us(delay_us);
  tracker::FastrakSession session(stream, clock, serial_session());
  std::vector<FastrakPose> poses;
  while (clock.now_us() < static_cast<std::int64_t>(seconds * 1e6)) {
    for (auto p = session.poll(); p.ok(); p = session.poll()) poses.push_back(*p);
    clock.advance_us(1'000);
  }
  EXPECT_EQ(stream.device().counters().command_errors, 0u);
  EXPECT_EQ(session.counters().streams_started, 1u);
  return poses;
}

TEST_F(PolhemusUsbTest, UsbLibertyGivesTheSerialLibertysPosesForTheSameMotion) {
  // (a) the USB Liberty: the model powers up as it is plugged in.
  fake_.set_device(liberty_unit(), motion());
  plug(hal::kPolhemusVendorId, 0xff12, 3);
  start_station("");
  ASSERT_EQ(session_config_.model, tracker::TrackerModel::liberty);
  const bool got = run_until(15.0, [&] { return poses_.size() >= 600; });
  ASSERT_TRUE(got) << "poses " << poses_.size() << describe();
  EXPECT_EQ(fake_.device()->counters().command_errors, 0u) << describe();

  // (b) the serial Liberty, long enough to cover (a)'s cycles. The model gives its
  // 120 Hz cycles to the active stations in turn from the first cycle after `C`, so which
  // station a cycle carries depends on when `C` came: (a) on the real clock may stream
  // station 1 on the odd cycles or the even ones. (b) is run both ways (the station
  // starting the unit one cycle later), and (a) is compared with the run in its phase.
  std::vector<FastrakPose> serial = serial_poses(15.0, 0);
  ASSERT_GE(serial.size(), 1000u);
  Alignment a = align(poses_, serial);
  if (a.compared == 0) {
    serial = serial_poses(15.0, 8'334);
    a = align(poses_, serial);
  }
  std::fprintf(stderr,
               "USB %zu poses, serial %zu; %zu USB poses before the serial stream began, "
               "%zu compared, %zu unequal\n",
               poses_.size(), serial.size(), a.before_overlap, a.compared, a.unequal);
  // The serial start-up pauses are longer (100 ms against USB's 50 ms): at most a
  // second of cycles streams over USB before the serial unit streams.
  EXPECT_LE(a.before_overlap, 120u);
  EXPECT_GE(a.compared, 450u);
  EXPECT_EQ(a.unequal, 0u) << a.first_difference;
  bool pressed = false;
  bool moved = false;
  for (std::size_t i = a.before_overlap; i < poses_.size(); ++i) {
    pressed = pressed || poses_[i].button;
    moved = moved || poses_[i].position != poses_[a.before_overlap].position;
  }
  EXPECT_TRUE(pressed) << "the stylus press is among the poses compared";
  EXPECT_TRUE(moved);

  // The comparison can fail: the serial side's poses in centimetres (a unit whose
  // units differ) share no pose with the USB side's.
  std::vector<FastrakPose> centimetres = serial;
  for (FastrakPose& p : centimetres)
    for (float& v : p.position) v *= 2.54f;
  EXPECT_EQ(align(poses_, centimetres).before_overlap, poses_.size());
}

}  // namespace
}  // namespace twister::station_app
