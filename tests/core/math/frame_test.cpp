#include "twister/math/frame.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace twister::math {
namespace {

TEST(FrameTest, IdentityIsOrthonormal) {
  const Frame f = identity_frame(glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_TRUE(is_orthonormal(f));
  EXPECT_EQ(f.origin, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(f.w, glm::dvec3(0.0, 0.0, 1.0));
}

TEST(FrameTest, FromUvComputesWAsCross) {
  const Frame f =
      frame_from_uv(glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(f.w, glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_TRUE(is_orthonormal(f));
}

TEST(FrameTest, RejectsNonUnitAxis) {
  Frame f = identity_frame();
  f.u *= 1.0 + 1e-5;
  EXPECT_FALSE(is_orthonormal(f));
  f.u = glm::dvec3(1.0 + 1e-8, 0.0, 0.0);
  EXPECT_TRUE(is_orthonormal(f));
}

TEST(FrameTest, RejectsNonOrthogonalAxes) {
  Frame f = frame_from_uv(glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0),
                          glm::normalize(glm::dvec3(1e-4, 1.0, 0.0)));
  EXPECT_FALSE(is_orthonormal(f));
}

TEST(FrameTest, RejectsLeftHandedW) {
  Frame f = identity_frame();
  f.w = -f.w;
  EXPECT_FALSE(is_orthonormal(f));
}

TEST(FrameTest, RejectsNonFinite) {
  Frame f = identity_frame();
  f.origin.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(is_orthonormal(f));
  f = identity_frame();
  f.v.y = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(is_orthonormal(f));
}

}  // namespace
}  // namespace twister::math
