// The bin's floor as a physical limit (host/detect/verify/below_floor.hpp) and the interior box that
// keeps the floor out of the crops (bin_interior_box).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/verify/below_floor.hpp"

namespace binpick {
namespace {

// 1000 points on a vertical segment from z = 0 to z = 100 (model frame).
PointCloud column() {
  PointCloud c;
  for (int i = 0; i < 1000; ++i) c.points.emplace_back(0.0f, 0.0f, 0.1f * float(i));
  return c;
}

TEST(BelowFloor, CountsThePointsBelowTheFloorBeyondTheMargin) {
  // Camera looking down: the floor 1000 mm away, up = (0, 0, -1): up . p + 1000 = 0.
  const Eigen::Vector3d up(0, 0, -1);
  const double d = 1000;
  // The column standing on the floor (model z up = camera -z), its foot at the floor.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_DOUBLE_EQ(fraction_below_floor(column(), R, {0, 0, 1000}, up, d, 0.0), 0.0);
  // Sunk by 30 mm: the lowest 30 % lie below the floor; within a 10 mm margin, 20 %.
  EXPECT_NEAR(fraction_below_floor(column(), R, {0, 0, 1030}, up, d, 0.0), 0.30, 0.002);
  EXPECT_NEAR(fraction_below_floor(column(), R, {0, 0, 1030}, up, d, 10.0), 0.20, 0.002);
  // Lying on its side, anywhere on the floor plane: nothing below it.
  const Eigen::Matrix3d side = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_DOUBLE_EQ(fraction_below_floor(column(), side, {50, -20, 999}, up, d, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(fraction_below_floor(column(), side, {50, -20, 1001}, up, d, 0.0), 1.0);
  // A tilted floor: the same count in its own frame.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0).normalized()).toRotationMatrix();
  const Eigen::Vector3d up2 = tilt * up;
  const Eigen::Vector3d foot = tilt * Eigen::Vector3d(0, 0, 1030);
  EXPECT_NEAR(fraction_below_floor(column(), tilt * R, foot, up2, -up2.dot(tilt * Eigen::Vector3d(0, 0, 1000)), 0.0),
              0.30, 0.002);
  EXPECT_DOUBLE_EQ(fraction_below_floor(PointCloud{}, R, {0, 0, 0}, up, d, 0.0), 0.0);
}

TEST(BelowFloor, TheInteriorBoxStartsAboveTheFloorWhenAsked) {
  BinFit bin;
  bin.found = true;
  bin.interior = Eigen::Vector3d(600, 400, 300);
  const RegionBox keep_floor = bin_interior_box(bin, 5, 50);
  EXPECT_FLOAT_EQ(keep_floor.lo.z(), -5.0f);
  const RegionBox clear = bin_interior_box(bin, 5, 50, 3.0);
  EXPECT_FLOAT_EQ(clear.lo.z(), 3.0f);
  EXPECT_FLOAT_EQ(clear.lo.x(), -295.0f);
  EXPECT_FLOAT_EQ(clear.hi.z(), 350.0f);
}

}  // namespace
}  // namespace binpick
