// Pose conversion (docs/fastrak-protocol.md §4): Euler, direction cosines and quaternion agree;
// units, tool offset, hemisphere, boresight and world alignment.
#include "twister/tracker/pose_conversion.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace twister::tracker {
namespace {

void expect_near(const glm::dmat3& a, const glm::dmat3& b, double tol) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << c << "," << r;
}

TEST(PoseConversion, EulerMatchesSpecMatrixForAzimuth90) {
  // az 90: receiver x axis points along tracker +Y.
  const glm::dmat3 r = rotation_from_euler_deg(90, 0, 0);
  EXPECT_NEAR(r[0].y, 1.0, 1e-12);
  EXPECT_NEAR(r[1].x, -1.0, 1e-12);
  EXPECT_NEAR(r[2].z, 1.0, 1e-12);
  // el 90: x axis points along -Z (R(2,0) = -sin el).
  EXPECT_NEAR(rotation_from_euler_deg(0, 90, 0)[0].z, -1.0, 1e-12);
  // roll 90: y axis points along +Z (R(2,1) = cos el sin roll).
  EXPECT_NEAR(rotation_from_euler_deg(0, 0, 90)[1].z, 1.0, 1e-12);
}

RC_GTEST_PROP(PoseConversion, QuaternionDcmAndEulerAgree, ()) {
  std::array<float, 4> q{};
  double n = 0;
  do {
    for (float& x : q) x = static_cast<float>(*rc::gen::inRange(-1000, 1001)) / 1000.0f;
    n = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] +
                  double(q[3]) * q[3]);
  } while (n < 0.1);
  const glm::dmat3 rq = *rotation_from_quaternion(q);
  RC_ASSERT(std::fabs(glm::determinant(rq) - 1.0) < 1e-9);
  const glm::dvec3 e = euler_deg_from_rotation(rq);
  const glm::dmat3 re = rotation_from_euler_deg(e.x, e.y, e.z);
  std::array<float, 9> rows{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      rows[static_cast<std::size_t>(3 * r + c)] = static_cast<float>(rq[c][r]);
  const glm::dmat3 rd = *rotation_from_dcm(rows, 1e-4);
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      if (std::fabs(e.y) < 89.0) RC_ASSERT(std::fabs(re[c][r] - rq[c][r]) < 1e-9);
      RC_ASSERT(std::fabs(rd[c][r] - rq[c][r]) < 1e-6);
    }
  }
  // q and -q are the same rotation.
  const glm::dmat3 rn = *rotation_from_quaternion({-q[0], -q[1], -q[2], -q[3]});
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) RC_ASSERT(std::fabs(rn[c][r] - rq[c][r]) < 1e-12);
}

TEST(PoseConversion, DcmIsReorthonormalisedOrRejected) {
  // ASCII cosines with 4 decimals of a 45 degree azimuth.
  std::array<float, 9> rows{0.7071f, -0.7071f, 0, 0.7071f, 0.7071f, 0, 0, 0, 1.0f};
  auto r = rotation_from_dcm(rows, 0.01);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(glm::length((*r)[0]), 1.0, 1e-12);
  EXPECT_NEAR(glm::dot((*r)[0], (*r)[1]), 0.0, 1e-12);
  std::array<float, 9> skew{1, 0.2f, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_EQ(rotation_from_dcm(skew, 0.01).status().code(), StatusCode::data_loss);
  EXPECT_EQ(rotation_from_quaternion({0, 0, 0, 0}).status().code(), StatusCode::out_of_range);
}

TEST(PoseConversion, UnitsToolOffsetAndWorldAlignment) {
  FastrakPose p;
  p.station = 2;
  p.has_position = true;
  p.position = {10.0f, 0.0f, 0.0f};  // inches
  p.has.euler = true;
  p.euler_deg = {90.0f, 0.0f, 0.0f};
  PoseConversion conv;
  conv.tool_offset_m[1] = {0.1, 0.0, 0.0};  // 10 cm along the receiver's x axis
  auto f = to_station_frame(p, conv);
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->origin.x, 0.254, 1e-9);
  EXPECT_NEAR(f->origin.y, 0.1, 1e-9);  // receiver x = tracker +Y at az 90
  EXPECT_NEAR(f->u.y, 1.0, 1e-12);
  EXPECT_NEAR(glm::dot(glm::cross(f->u, f->v), f->w), 1.0, 1e-12);

  conv.units = Units::centimetres;
  conv.tool_offset_m[1] = {};
  conv.world_rotation = rotation_from_euler_deg(0, 0, 180);  // +Z down -> +Z up
  conv.world_translation_m = {0, 0, 1.0};
  p.position = {10.0f, 20.0f, 30.0f};
  f = to_station_frame(p, conv);
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->origin.x, 0.1, 1e-9);
  EXPECT_NEAR(f->origin.y, -0.2, 1e-9);
  EXPECT_NEAR(f->origin.z, 0.7, 1e-9);
}

TEST(PoseConversion, HemisphereAndBoresight) {
  FastrakPose p;
  p.station = 1;
  p.has_position = true;
  p.position = {-10.0f, 5.0f, 0.0f};
  p.has.quaternion = true;
  p.quaternion = {1, 0, 0, 0};
  PoseConversion conv;
  conv.hemisphere[0] = {1, 0, 0};
  auto f = to_station_frame(p, conv);
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->origin.x, 0.254, 1e-9);
  EXPECT_NEAR(f->origin.y, -0.127, 1e-9);

  // Boresight captured at az 30: that orientation now reads as identity.
  conv.boresight[0] = true;
  conv.boresight_rotation[0] = rotation_from_euler_deg(30, 0, 0);
  p.has.quaternion = false;
  p.has.euler = true;
  p.euler_deg = {30.0f, 0.0f, 0.0f};
  f = to_station_frame(p, conv);
  ASSERT_TRUE(f.ok());
  expect_near(glm::dmat3(f->u, f->v, f->w), glm::dmat3(1.0), 1e-6);

  // A tool offset stays along the receiver's true axes under a boresight: the tip of a
  // stylus turned az 30 is 0.1 m along (cos 30, sin 30, 0), though it reads as unturned.
  conv.tool_offset_m[0] = {0.1, 0.0, 0.0};
  f = to_station_frame(p, conv);
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->origin.x, 0.254 + 0.1 * std::cos(3.14159265358979323846 / 6), 1e-6);
  EXPECT_NEAR(f->origin.y, -0.127 + 0.1 * std::sin(3.14159265358979323846 / 6), 1e-6);
  expect_near(glm::dmat3(f->u, f->v, f->w), glm::dmat3(1.0), 1e-6);
}

TEST(PoseConversion, MissingItemsAreReported) {
  FastrakPose p;
  p.station = 1;
  PoseConversion conv;
  EXPECT_EQ(to_station_frame(p, conv).status().code(), StatusCode::failed_precondition);
  p.has_position = true;
  EXPECT_EQ(to_station_frame(p, conv).status().code(), StatusCode::failed_precondition);
  p.station = 5;
  EXPECT_EQ(to_station_frame(p, conv).status().code(), StatusCode::invalid_argument);
}

}  // namespace
}  // namespace twister::tracker
