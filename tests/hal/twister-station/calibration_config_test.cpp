// Issue 23: [tracker.calibration] through the station's tracker path. Each key is parsed
// from station.toml, set up by make_station_setup, and the core Station runs against the
// simulated Fastrak (twister-sim's device model, in-process, virtual time): a known pose
// of the scenario goes in, and the pose the core applies to the hand is checked against
// the expected one (hemisphere, boresight, tip offset, filters, work frame). Bad values
// are refused with a message naming the key (label devices).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"
#include "fakes/fake_button_source.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_storage.hpp"
#include "station_setup.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#include "twister/station/station.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::station_app {
namespace {

using ::testing::HasSubstr;

constexpr double kInch = 0.0254;
constexpr std::size_t kGrid = 5;
using Mesh = mesh::MeshWithStorage<kGrid * kGrid, 2 * kGrid * kGrid>;
using Work = session::SculptStorageArrays<kGrid * kGrid, kGrid * kGrid, 2048, 8>;

std::string config_with(const std::string& calibration) {
  return "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"sim\"\n"
         "[buttons]\nbackend = \"sim\"\n[tracker.calibration]\n" +
         calibration + "\n";
}

station::StationConfig setup_of(const std::string& calibration) {
  const auto r = parse_station_config(config_with(calibration), "t.toml");
  EXPECT_TRUE(r.ok()) << test::messages(r);
  auto setup = make_station_setup(r.config);
  EXPECT_TRUE(setup) << setup.error().message;
  station::StationConfig c = *setup;
  // Simulator timings (the unit's real waits are seconds).
  c.session.ladder_char_pause_us = 20'000;
  c.session.reset_wait_us = 600'000;
  c.session.settle_us = 50'000;
  c.session.reply_timeout_us = 300'000;
  c.session.command_pause_us = 50'000;
  c.session.filter_pause_us = 600'000;  // the simulated unit is deaf 500 ms after x / v
  return c;
}

struct SimRun {
  Pose pose;                  // hand 0 (receiver 1) at the end
  glm::dvec3 truth_origin_m;  // the scenario's receiver 1 at the end (transmitter frame)
  glm::dmat3 truth_rotation{1.0};
  sim::FilterParams position_filter;
  bool valid = false;
};

// The station on the simulated unit for `seconds` of virtual time; hand 0's last pose.
SimRun run(const station::StationConfig& cfg, const std::string& scenario, double seconds) {
  sim::Scenario sc;
  std::string err;
  EXPECT_TRUE(sim::parse_scenario(scenario, sc, err)) << err;
  twister::test::FakeClock clock(1'000'000);
  sim::SimFastrakStream stream(clock, sim::FastrakDeviceConfig{}, sc);
  twister::test::FakeButtonSource buttons;
  twister::test::FakeStorage storage;
  auto mesh = std::make_unique<Mesh>();
  auto work = std::make_unique<Work>();
  station::Station st(stream, buttons, clock, storage, *mesh, work->spans(), cfg);
  EXPECT_TRUE(st.start().ok());
  for (int tick = 0; tick < static_cast<int>(seconds * 1000); ++tick) {
    EXPECT_TRUE(st.poll().ok());
    clock.advance_us(1'000);
  }
  SimRun r;
  r.valid = st.hand_valid(0, clock.now_us());
  r.pose = st.hand_pose(0);
  const sim::HandSample s = sim::sample(sc, 1, stream.device().scenario_time_s(clock.now_us()));
  r.truth_origin_m = glm::dvec3(s.position_in[0], s.position_in[1], s.position_in[2]) * kInch;
  r.truth_rotation =
      tracker::rotation_from_euler_deg(s.euler_deg[0], s.euler_deg[1], s.euler_deg[2]);
  r.position_filter = stream.device().position_filter();
  return r;
}

// Receiver 1 rests at (10, -4, 2) in, turned (az 10, el 5, roll 0); receiver 2 rests.
constexpr const char* kRest = "receivers 2\nkey 0 1 10 -4 2 10 5 0\nkey 0 2 12 4 -3 -40 10 20\n";
const glm::dvec3 kRestOrigin = glm::dvec3(10, -4, 2) * kInch;
const glm::dmat3 kRestR = tracker::rotation_from_euler_deg(10, 5, 0);

void expect_near(const glm::dvec3& got, const glm::dvec3& want, double tol, const char* what) {
  EXPECT_LT(glm::length(got - want), tol)
      << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x
      << ", " << want.y << ", " << want.z << ")";
}

void expect_pose(const SimRun& r, const glm::dvec3& origin, const glm::dmat3& axes) {
  ASSERT_TRUE(r.valid);
  expect_near(r.pose.origin, origin, 1e-5, "origin");
  expect_near(r.pose.u, axes[0], 1e-5, "u");
  expect_near(r.pose.v, axes[1], 1e-5, "v");
  expect_near(r.pose.w, axes[2], 1e-5, "w");
  std::printf("  origin (%.6f, %.6f, %.6f) m, u (%.5f, %.5f, %.5f)\n", r.pose.origin.x,
              r.pose.origin.y, r.pose.origin.z, r.pose.u.x, r.pose.u.y, r.pose.u.z);
}

TEST(CalibrationOnSim, NoCalibrationIsTheTransmitterFrame) {
  expect_pose(run(setup_of(""), kRest, 3.0), kRestOrigin, kRestR);
}

TEST(CalibrationOnSim, HemisphereDecidesTheSignOfThePosition) {
  // The hand behind the transmitter (-X): the default +X hemisphere mirrors it through
  // the origin (as the unit does), hemisphere = [-1, 0, 0] reports it where it is.
  const std::string behind = "receivers 2\nkey 0 1 -10 4 -2 10 5 0\nkey 0 2 12 4 -3 -40 10 20\n";
  expect_pose(run(setup_of(""), behind, 3.0), kRestOrigin, kRestR);
  expect_pose(run(setup_of("hemisphere = [-1, 0, 0]"), behind, 3.0), -kRestOrigin, kRestR);
  // Lower hemisphere (+Z down): a hand above the transmitter (z < 0) is mirrored.
  const std::string above = "receivers 2\nkey 0 1 10 -4 -2 10 5 0\nkey 0 2 12 4 3 -40 10 20\n";
  expect_pose(run(setup_of("hemisphere = [0, 0, 1]"), above, 3.0), glm::dvec3(-10, 4, 2) * kInch,
              kRestR);
}

TEST(CalibrationOnSim, TipOffsetMovesThePointAlongTheReceiverAxes) {
  // 10 cm along the stylus's own x axis and 2 cm along its z axis.
  expect_pose(run(setup_of("tip_offset = [0.1, 0.0, 0.02]"), kRest, 3.0),
              kRestOrigin + 0.1 * kRestR[0] + 0.02 * kRestR[2], kRestR);
}

TEST(CalibrationOnSim, BoresightZeroesTheAnglesAtItsOrientation) {
  // Boresight at the receiver's own orientation: it reads as the identity.
  expect_pose(run(setup_of("boresight = [10, 5, 0]"), kRest, 3.0), kRestOrigin, glm::dmat3(1.0));
  // With reference angles: it reads as them.
  expect_pose(run(setup_of("boresight = [10, 5, 0]\nboresight_reference = [30, 0, 0]"), kRest, 3.0),
              kRestOrigin, tracker::rotation_from_euler_deg(30, 0, 0));
}

TEST(CalibrationOnSim, AllKeysTogether) {
  // Tip, boresight and work frame at once: the tip stays where the stylus points (the
  // boresight changes how the attitude reads, not where the tip is), then the work frame
  // moves it. Work frame: origin at the transmitter, x = transmitter y, y = transmitter x.
  const SimRun r = run(setup_of("tip_offset = [0.1, 0.0, 0.0]\nboresight = [10, 5, 0]\n"
                                "position_filter = \"off\"\n"
                                "[tracker.calibration.work_frame]\norigin = [0, 0, 0]\n"
                                "x_axis = [0, 1, 0]\ny_axis = [1, 0, 0]"),
                       kRest, 3.0);
  const glm::dmat3 to_model(glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1));
  expect_pose(r, to_model * (kRestOrigin + 0.1 * kRestR[0]), to_model);
}

TEST(CalibrationOnSim, WorkFrameMovesAndTurnsEveryPoseIntoTheModelFrame) {
  // The model's origin at the resting receiver; its +X the transmitter's +Y, its +Y the
  // transmitter's +X, so its +Z (up) is the transmitter's -Z (the transmitter's +Z
  // points down).
  const SimRun r =
      run(setup_of("[tracker.calibration.work_frame]\norigin = [0.254, -0.1016, 0.0508]\n"
                   "x_axis = [0, 1, 0]\ny_axis = [1, 0, 0]"),
          kRest, 3.0);
  const glm::dmat3 to_model(glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1));
  expect_pose(r, glm::dvec3(0.0), to_model * kRestR);
  // A point 10 cm above the transmitter's origin stands 10 cm up in the model.
  tracker::PoseConversion conv;
  apply_work_frame(WorkFrameConfig{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}, conv);
  expect_near(conv.world_rotation * glm::dvec3(0, 0, -0.1) + conv.world_translation_m,
              glm::dvec3(0, 0, 0.1), 1e-12, "up");
}

TEST(CalibrationOnSim, PositionFilterReachesTheUnitAndLagsAMovingHand) {
  // Receiver 1 moves 10 in/s along x; the unit's filtered pose trails the truth.
  const std::string moving =
      "receivers 2\nkey 0 1 10 0 0 0 0 0\nkey 10 1 110 0 0 0 0 0\nkey 0 2 12 4 -3 -40 10 20\n";
  const SimRun off = run(setup_of("position_filter = \"off\""), moving, 4.0);
  const SimRun medium = run(setup_of("position_filter = \"medium\""), moving, 4.0);
  const SimRun custom =
      run(setup_of("position_filter = { f = 0.2, flow = 0.05, fhigh = 0.5, factor = 0.95 }"),
          moving, 4.0);
  ASSERT_TRUE(off.valid && medium.valid && custom.valid);
  EXPECT_EQ(off.position_filter.flow, 1.0);
  EXPECT_NEAR(medium.position_filter.flow, 0.2, 1e-9);
  EXPECT_NEAR(custom.position_filter.fhigh, 0.5, 1e-9);
  const double lag_off = off.truth_origin_m.x - off.pose.origin.x;
  const double lag_medium = medium.truth_origin_m.x - medium.pose.origin.x;
  const double lag_custom = custom.truth_origin_m.x - custom.pose.origin.x;
  std::printf("  lag behind the truth at 10 in/s: off %.4f m, medium %.4f m, heavy-ish %.4f m\n",
              lag_off, lag_medium, lag_custom);
  EXPECT_GT(lag_medium, lag_off + 0.002);
  EXPECT_GT(lag_custom, lag_medium);
}

TEST(CalibrationOnSim, AttitudeFilterLagsATurningHand) {
  // Receiver 1 turns 10 degrees/s in azimuth; the filtered attitude trails the truth.
  const std::string turning =
      "receivers 2\nkey 0 1 10 0 0 0 0 0\nkey 10 1 10 0 0 100 0 0\nkey 0 2 12 4 -3 -40 10 20\n";
  double lag_deg[2] = {};
  const char* settings[2] = {"attitude_filter = \"off\"", "attitude_filter = \"medium\""};
  for (int i = 0; i < 2; ++i) {
    const SimRun r = run(setup_of(settings[i]), turning, 4.0);
    ASSERT_TRUE(r.valid);
    const double az = std::atan2(r.pose.u.y, r.pose.u.x) * 180.0 / 3.14159265358979323846;
    const double truth = tracker::euler_deg_from_rotation(r.truth_rotation).x;
    lag_deg[i] = truth - az;
  }
  std::printf("  attitude lag behind the truth at 10 deg/s: off %.3f deg, medium %.3f deg\n",
              lag_deg[0], lag_deg[1]);
  EXPECT_GT(lag_deg[1], lag_deg[0] + 0.05);
}

// The messages for bad values.
std::string errors_of(const std::string& calibration) {
  const auto r = parse_station_config(config_with(calibration), "t.toml");
  EXPECT_FALSE(r.ok()) << calibration;
  return test::messages(r);
}

TEST(CalibrationConfig, BadValuesAreRefusedWithTheKeyAndTheExpectedForm) {
  EXPECT_THAT(errors_of("[tracker.calibration.work_frame]\norigin = [0, 0, 0]\n"
                        "x_axis = [1, 0, 0]\ny_axis = [1, 1, 0]"),
              HasSubstr("tracker.calibration.work_frame.y_axis: expected a direction "
                        "perpendicular to x_axis (within 2 degrees), got 45 degrees"));
  EXPECT_THAT(errors_of("[tracker.calibration.work_frame]\norigin = [0, 0, 0]\n"
                        "x_axis = [0, 0, 0]\ny_axis = [1, 1, 0]"),
              HasSubstr("work_frame.x_axis: expected a non-zero direction"));
  EXPECT_THAT(errors_of("[tracker.calibration.work_frame]\norigin = [0, 0, 0]\nx_axis = [1, 0, 0]"),
              HasSubstr("tracker.calibration.work_frame.y_axis: missing"));
  EXPECT_THAT(errors_of("[tracker.calibration.work_frame]\norigin = [0, 0, 20]\n"
                        "x_axis = [1, 0, 0]\ny_axis = [0, 1, 0]"),
              HasSubstr("work_frame.origin: expected an array of three numbers from -10 to 10, "
                        "got 20"));
  EXPECT_THAT(errors_of("hemisphere = [0, 0, 0]"),
              HasSubstr("tracker.calibration.hemisphere: expected a direction of -1, 0 or 1"));
  EXPECT_THAT(errors_of("hemisphere = [1, 0]"), HasSubstr("got 2 elements"));
  EXPECT_THAT(errors_of("tip_offset = [0.6, 0, 0]"),
              HasSubstr("tracker.calibration.tip_offset: expected an array of three numbers from "
                        "-0.5 to 0.5, got 0.6"));
  EXPECT_THAT(errors_of("boresight = [0, 95, 0]"),
              HasSubstr("tracker.calibration.boresight: expected an elevation"));
  EXPECT_THAT(errors_of("boresight_reference = [0, 0, 0]"),
              HasSubstr("needs tracker.calibration.boresight"));
  EXPECT_THAT(errors_of("position_filter = \"strong\""),
              HasSubstr("tracker.calibration.position_filter: expected one of \"unit\" \"off\" "
                        "\"medium\""));
  EXPECT_THAT(errors_of("attitude_filter = { f = 0.2, flow = 0.9, fhigh = 0.5, factor = 0.9 }"),
              HasSubstr("tracker.calibration.attitude_filter: expected flow < fhigh"));
  EXPECT_THAT(errors_of("attitude_filter = { f = 0.2, flow = 0.1, fhigh = 0.5 }"),
              HasSubstr("attitude_filter.factor"));
  EXPECT_THAT(errors_of("tip_ofset = [0, 0, 0]"), HasSubstr("tracker.calibration.tip_ofset"));
}

TEST(CalibrationConfig, DefaultsLeaveTheUnitAndThePosesAlone) {
  const auto r = parse_station_config(config_with(""), "t.toml");
  ASSERT_TRUE(r.ok()) << test::messages(r);
  const auto setup = make_station_setup(r.config);
  ASSERT_TRUE(setup);
  EXPECT_EQ(setup->session.position_filter.mode, tracker::FilterSetting::Mode::leave);
  EXPECT_EQ(setup->session.hemisphere[0], (std::array<int, 3>{1, 0, 0}));
  EXPECT_EQ(setup->conversion.world_rotation, glm::dmat3(1.0));
  EXPECT_EQ(setup->conversion.world_translation_m, glm::dvec3(0.0));
  EXPECT_FALSE(setup->conversion.boresight[0]);
}

}  // namespace
}  // namespace twister::station_app

namespace twister::station_app {
namespace {

// The working volume the display frames (link `workspace`): the configured box, the
// default above the work frame's origin (+Z up), or the tracker's range on the
// hemisphere's side of the transmitter (+Z down), and the box's mistakes.
link::Workspace workspace_from(const std::string& calibration) {
  const auto r = parse_station_config(config_with(calibration), "t.toml");
  EXPECT_TRUE(r.ok()) << test::messages(r);
  return workspace_of(r.config.tracker.calibration);
}

TEST(CalibrationConfig, WorkVolumeIsWhatTheDisplayFrames) {
  const link::Workspace none = workspace_from("");
  EXPECT_EQ(none.flags, 0);
  EXPECT_EQ(none.up, glm::vec3(0.0F, 0.0F, -1.0F));
  EXPECT_GT(none.min.x, 0.0F) << "in front of the transmitter (hemisphere +X)";
  EXPECT_NEAR(none.max.x, 0.76F, 1e-5F);
  const link::Workspace below = workspace_from("hemisphere = [0, 0, 1]");
  EXPECT_GT(below.min.z, 0.0F) << "below the transmitter";
  const std::string frame =
      "[tracker.calibration.work_frame]\norigin = [0.5, 0, 0.3]\nx_axis = [1, 0, 0]\n"
      "y_axis = [0, -1, 0]\n";
  const link::Workspace calibrated = workspace_from(frame);
  EXPECT_EQ(calibrated.flags, link::kWorkspaceCalibrated);
  EXPECT_EQ(calibrated.up, glm::vec3(0.0F, 0.0F, 1.0F));
  EXPECT_EQ(calibrated.min, glm::vec3(-0.3F, -0.3F, 0.0F));
  EXPECT_EQ(calibrated.max, glm::vec3(0.3F, 0.3F, 0.4F));
  const link::Workspace configured = workspace_from(
      frame + "[tracker.calibration.work_volume]\nmin = [-0.5, -0.2, 0]\nmax = [0.5, 0.2, 0.6]\n");
  EXPECT_EQ(configured.flags, link::kWorkspaceCalibrated | link::kWorkspaceConfigured);
  EXPECT_EQ(configured.min, glm::vec3(-0.5F, -0.2F, 0.0F));
  EXPECT_EQ(configured.max, glm::vec3(0.5F, 0.2F, 0.6F));
}

TEST(CalibrationConfig, BadWorkVolumesAreRefusedWithTheKey) {
  EXPECT_THAT(errors_of("[tracker.calibration.work_volume]\nmin = [0, 0, 0]"),
              HasSubstr("tracker.calibration.work_volume.max: missing"));
  EXPECT_THAT(errors_of("[tracker.calibration.work_volume]\nmin = [0, 0, 0]\nmax = [1, 1, 0]"),
              HasSubstr("tracker.calibration.work_volume.max: expected each coordinate at least "
                        "0.01 above min's, got 0 against 0"));
  EXPECT_THAT(errors_of("[tracker.calibration.work_volume]\nmin = [0, 0, 0]\nmax = [1, 1, 11]"),
              HasSubstr("work_volume.max: expected an array of three numbers from -10 to 10"));
}

}  // namespace
}  // namespace twister::station_app
