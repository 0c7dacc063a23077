// Issue 23: the simulated Fastrak models the calibration commands on the poses it
// reports, not only on the bytes it accepts: `H` reports a hand in the configured
// half-space (mirrored through the transmitter), `N` moves the reported point to the
// tip offset along the receiver's axes, `B` zeroes the angles at the attitude of the
// moment (`G` sets the angles it reads as instead, `b` undoes it). Each is checked on a
// known pose, and against the station's host-side pose conversion of the same settings
// (tracker::to_station_frame: hemisphere, tool offset, boresight) (label devices).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {
namespace {

using tracker::Item;
using tracker::OutputList;

// Receiver 1 rests at (10, -4, 2) in, turned az 10, el 5, roll 0.
constexpr const char* kRest = "receivers 1\nkey 0 1 10 -4 2 10 5 0\n";

// The last station-1 pose after `commands` and a poll `P`, in binary (`f`) so the
// numbers are floats: position (inches) and Euler angles (degrees).
tracker::FastrakPose pose_after(const std::string& commands, const char* scenario = kRest) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(parse_scenario(scenario, sc, err)) << err;
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  dev.command_time_us = instant_commands();
  FastrakDevice device(dev, sc, 0);
  const std::string all = "f" + commands + "P";
  device.receive(reinterpret_cast<const std::byte*>(all.data()), all.size(), 10);
  std::vector<std::byte> out;
  device.advance(1'000'000, out);
  tracker::FastrakConfig pc;
  pc.format = tracker::Format::binary;
  pc.stations[0].enabled = true;
  pc.stations[0].list = OutputList::of({Item::position, Item::euler, Item::crlf});
  tracker::FastrakParser parser(pc);
  tracker::FastrakPose last;
  bool any = false;
  std::span<const std::byte> in(out);
  while (!in.empty()) {
    auto ev = parser.next(in);
    if (!ev.ok()) continue;
    if (ev->kind == tracker::EventKind::pose && ev->pose.station == 1) {
      last = ev->pose;
      any = true;
    }
    if (ev->kind == tracker::EventKind::reply) {
      ADD_FAILURE() << "a reply to " << ev->reply.command << " code " << ev->reply.error_code;
    }
  }
  EXPECT_TRUE(any) << "no pose";
  return last;
}

glm::dvec3 position_in(const tracker::FastrakPose& p) {
  return {p.position[0], p.position[1], p.position[2]};
}
glm::dvec3 euler(const tracker::FastrakPose& p) {
  return {p.euler_deg[0], p.euler_deg[1], p.euler_deg[2]};
}

void expect_near(const glm::dvec3& got, const glm::dvec3& want, double tol, const char* what) {
  EXPECT_LT(glm::length(got - want), tol)
      << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x
      << ", " << want.y << ", " << want.z << ")";
  std::printf("  %s (%.4f, %.4f, %.4f)\n", what, got.x, got.y, got.z);
}

// The station's host-side conversion of the raw pose (no unit-side calibration).
Pose host_side(const tracker::PoseConversion& conv) {
  tracker::FastrakPose raw = pose_after("");
  auto f = tracker::to_station_frame(raw, conv);
  EXPECT_TRUE(f.ok());
  return *f;
}

Pose as_station_frame(const tracker::FastrakPose& p) {
  tracker::PoseConversion conv;
  conv.format = tracker::Format::binary;
  auto f = tracker::to_station_frame(p, conv);
  EXPECT_TRUE(f.ok());
  return *f;
}

const glm::dvec3 kRestIn(10, -4, 2);
const glm::dmat3 kRestR = tracker::rotation_from_euler_deg(10, 5, 0);

TEST(FastrakCalibrationModel, NoCommandsReportTheScenario) {
  const auto p = pose_after("");
  expect_near(position_in(p), kRestIn, 1e-4, "position in");
  expect_near(euler(p), glm::dvec3(10, 5, 0), 1e-3, "angles deg");
}

TEST(FastrakCalibrationModel, HemisphereFlipsTheSigns) {
  expect_near(position_in(pose_after("H1,-1,0,0\r")), -kRestIn, 1e-4, "H1,-1,0,0 position in");
  expect_near(position_in(pose_after("H1,0,0,1\r")), kRestIn, 1e-4, "H1,0,0,1 position in");
  expect_near(position_in(pose_after("H1,0,0,-1\r")), -kRestIn, 1e-4, "H1,0,0,-1 position in");
  // The host's mirroring agrees.
  tracker::PoseConversion conv;
  conv.format = tracker::Format::binary;
  conv.hemisphere[0] = {-1, 0, 0};
  expect_near(host_side(conv).origin / 0.0254, -kRestIn, 1e-4, "host hemisphere in");
}

TEST(FastrakCalibrationModel, TipOffsetMovesTheReportedPoint) {
  // 4 in along the receiver's x axis, 1 in along its z axis; the angles stay.
  const auto p = pose_after("N1,4,0,1\r");
  const glm::dvec3 want = kRestIn + 4.0 * kRestR[0] + 1.0 * kRestR[2];
  expect_near(position_in(p), want, 1e-4, "N1,4,0,1 position in");
  expect_near(euler(p), glm::dvec3(10, 5, 0), 1e-3, "N1,4,0,1 angles deg");
  // In centimetres (`u`): the offset is read in the current units.
  const auto cm = pose_after("uN1,10.16,0,2.54\r");
  expect_near(position_in(cm) / 2.54, want, 1e-4, "uN1,10.16,0,2.54 position in");
  // The station's tool offset on the raw pose gives the same point.
  tracker::PoseConversion conv;
  conv.format = tracker::Format::binary;
  conv.tool_offset_m[0] = glm::dvec3(4, 0, 1) * 0.0254;
  expect_near(host_side(conv).origin / 0.0254, want, 1e-4, "host tip offset in");
}

TEST(FastrakCalibrationModel, BoresightZeroesTheAngles) {
  const auto b = pose_after("B1\r");
  expect_near(euler(b), glm::dvec3(0, 0, 0), 1e-3, "B1 angles deg");
  expect_near(position_in(b), kRestIn, 1e-4, "B1 position in");
  // With reference angles it reads as them; `b` undoes it.
  expect_near(euler(pose_after("G1,30,0,0\rB1\r")), glm::dvec3(30, 0, 0), 1e-3,
              "G1,30,0,0 B1 angles deg");
  expect_near(euler(pose_after("B1\rb1\r")), glm::dvec3(10, 5, 0), 1e-3, "B1 b1 angles deg");
  // The station's host-side boresight at the same attitude agrees.
  tracker::PoseConversion conv;
  conv.format = tracker::Format::binary;
  conv.boresight[0] = true;
  conv.boresight_rotation[0] = kRestR;
  conv.boresight_reference_deg[0] = {30, 0, 0};
  const Pose host = host_side(conv);
  const Pose unit = as_station_frame(pose_after("G1,30,0,0\rB1\r"));
  expect_near(host.u, unit.u, 1e-5, "host vs unit boresight u");
  expect_near(host.w, unit.w, 1e-5, "host vs unit boresight w");
}

TEST(FastrakCalibrationModel, BadCalibrationCommandsAreRefused) {
  Scenario sc;
  std::string err;
  ASSERT_TRUE(parse_scenario(kRest, sc, err)) << err;
  FastrakDeviceConfig dev;
  dev.reset_time_us = 0;
  dev.command_time_us = instant_commands();
  FastrakDevice device(dev, sc, 0);
  const std::string cmds = "N1,1,x,0\rG1,0,95,0\rN5,0,0,0\rN1,1\r";
  device.receive(reinterpret_cast<const std::byte*>(cmds.data()), cmds.size(), 10);
  std::vector<std::byte> out;
  device.advance(1'000'000, out);
  tracker::FastrakConfig pc;
  pc.stations[0].enabled = true;
  tracker::FastrakParser parser(pc);
  std::vector<int> codes;
  std::span<const std::byte> in(out);
  while (!in.empty()) {
    auto ev = parser.next(in);
    if (ev.ok() && ev->kind == tracker::EventKind::reply) codes.push_back(ev->reply.error_code);
  }
  EXPECT_EQ(codes, (std::vector<int>{-2, -3, -3, -1}));
}

}  // namespace
}  // namespace twister::sim
