#include "figure8_experiment.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace twister::cli {
namespace {

TEST(Figure8ExperimentTest, CountsProperCrossingsOnly) {
  EXPECT_EQ(count_self_intersections({{0, 0}, {1, 0}, {2, 0}, {3, 0}}), 0u);
  // A loop: the last segment crosses the first.
  EXPECT_EQ(count_self_intersections({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, -1}}), 1u);
  // Adjacent segments share a point: not a crossing. Touching at an end: not proper.
  EXPECT_EQ(count_self_intersections({{0, 0}, {1, 0}, {1, 1}, {0.5, 0}}), 0u);
  // A figure eight drawn as a bow tie crosses once.
  EXPECT_EQ(count_self_intersections({{0, 0}, {1, 1}, {1, 0}, {0, 1}, {0, 0}}), 1u);
}

TEST(Figure8ExperimentTest, SharpestTurn) {
  EXPECT_NEAR(sharpest_turn_deg({{0, 0}, {1, 0}, {1, 1}}), 90.0, 1e-12);
  EXPECT_NEAR(sharpest_turn_deg({{0, 0}, {1, 0}, {2, 0}}), 0.0, 1e-12);
  EXPECT_NEAR(sharpest_turn_deg({{0, 0}, {1, 0}, {0, 0}}), 180.0, 1e-12);
}

TEST(Figure8ExperimentTest, GrabPointsFollowTheHands) {
  const Figure8Setup setup{};
  Figure8Curve c;
  ASSERT_TRUE(run_figure8_curve(setup, 90, math::WarpMethod::twister, c).ok());
  ASSERT_EQ(c.points.size(), 2001u);
  // x = -0.5 is point 500, x = 0.5 point 1500; both lifted by 0.6.
  EXPECT_NEAR(c.points[500].x, -0.5, 1e-5);
  EXPECT_NEAR(c.points[500].y, 0.6, 1e-5);
  EXPECT_NEAR(c.points[1500].x, 0.5, 1e-5);
  EXPECT_NEAR(c.points[1500].y, 0.6, 1e-5);
  // Outside both balls nothing moves.
  EXPECT_EQ(c.points[0].x, -1.0);
  EXPECT_EQ(c.points[0].y, 0.0);
  EXPECT_EQ(c.intersections, 0u);
}

TEST(Figure8ExperimentTest, HalfTurnSenseFollowsTheSign) {
  const Figure8Setup setup{};
  Figure8Curve plus, minus;
  ASSERT_TRUE(run_figure8_curve(setup, 180, math::WarpMethod::twister, plus).ok());
  ASSERT_TRUE(run_figure8_curve(setup, -180, math::WarpMethod::twister, minus).ok());
  // Same end poses, opposite senses: the point half way into hand 1's ball goes to
  // opposite sides.
  const auto& p = plus.points[375];
  const auto& m = minus.points[375];
  EXPECT_GT(std::abs(p.y - m.y), 0.1);
}

}  // namespace
}  // namespace twister::cli
