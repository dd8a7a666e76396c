// BOP's MSSD and MSPD on poses whose errors are known by hand, and BOP's discretised symmetry
// transformations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/eval/metrics/bop_pose_error.hpp"

namespace binpick::eval {
namespace {

// The 8 corners of a cube of side 20 mm centred on the origin.
std::vector<Eigen::Vector3d> cube() {
  std::vector<Eigen::Vector3d> v;
  for (int x : {-10, 10})
    for (int y : {-10, 10})
      for (int z : {-10, 10}) v.emplace_back(x, y, z);
  return v;
}

// 360 points on a circle of radius 10 about the z axis at heights -5 and 5 (a cylinder's rims).
std::vector<Eigen::Vector3d> cylinder_rims() {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 360; ++i)
    for (double z : {-5.0, 5.0}) {
      const double a = i * std::numbers::pi / 180.0;
      v.emplace_back(10 * std::cos(a), 10 * std::sin(a), z);
    }
  return v;
}

Eigen::Matrix3d about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

PartSymmetries continuous_z(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  PartSymmetries s;
  s.continuous.push_back({Eigen::Vector3d::UnitZ(), offset});
  return s;
}

const std::vector<SymmetryTransform> kIdentityOnly{SymmetryTransform{}};

TEST(BopPoseError, MssdOfAShiftedCubeIsTheShift) {
  const RigidPose gt{about({1, 2, 3}, 0.7), {10, 20, 600}};
  const RigidPose est{gt.R, gt.t + Eigen::Vector3d(3, 4, 0)};
  EXPECT_NEAR(mssd(est, gt, cube(), kIdentityOnly), 5.0, 1e-12);
  EXPECT_NEAR(mssd(gt, gt, cube(), kIdentityOnly), 0.0, 1e-12);
}

TEST(BopPoseError, MssdOfARotatedCubeIsItsFarthestCornersPath) {
  // A quarter turn about z moves the corners (+-10, +-10, z) by sqrt(2) * 10 * sqrt(2) = 20 mm.
  const RigidPose gt{Eigen::Matrix3d::Identity(), {0, 0, 500}};
  const RigidPose est{about(Eigen::Vector3d::UnitZ(), std::numbers::pi / 2), gt.t};
  EXPECT_NEAR(mssd(est, gt, cube(), kIdentityOnly), 20.0, 1e-9);
}

TEST(BopPoseError, MspdOfASidewaysShiftIsLargestForTheNearestCorner) {
  // A shift of 1 mm along x moves a point at depth Z by fx / Z pixels: most at Z = 490.
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  const RigidPose gt{Eigen::Matrix3d::Identity(), {0, 0, 500}};
  const RigidPose est{gt.R, gt.t + Eigen::Vector3d(1, 0, 0)};
  EXPECT_NEAR(mspd(est, gt, K, cube(), kIdentityOnly), 500.0 / 490.0, 1e-9);
  // A shift along the viewing ray of the centre moves the corners' images apart from it.
  const RigidPose nearer{gt.R, {0, 0, 400}};
  const double expected = std::hypot(500.0 * 10 / 390 - 500.0 * 10 / 490,
                                     500.0 * 10 / 390 - 500.0 * 10 / 490);
  EXPECT_NEAR(mspd(nearer, gt, K, cube(), kIdentityOnly), expected, 1e-9);
}

TEST(BopPoseError, RotationAboutTheSymmetryAxisIsNoErrorOnlyWithTheSymmetry) {
  const auto syms = bop_symmetry_transforms(continuous_z());
  const RigidPose gt{about({1, 0, 1}, 0.4), {0, 0, 600}};
  // 7 steps of BOP's discretisation (2 pi / 315): one of its transformations exactly.
  const double on_grid = 7 * 2 * std::numbers::pi / 315;
  const RigidPose est{gt.R * about(Eigen::Vector3d::UnitZ(), on_grid), gt.t};
  EXPECT_NEAR(mssd(est, gt, cylinder_rims(), syms), 0.0, 1e-9);
  // Without the symmetry: the rim points move by the chord 2 r sin(angle / 2).
  EXPECT_NEAR(mssd(est, gt, cylinder_rims(), kIdentityOnly), 20 * std::sin(on_grid / 2), 1e-3);
  // Off the grid the error is at most the chord of half a step (r * pi / 315 = 0.0997 mm).
  const RigidPose off{gt.R * about(Eigen::Vector3d::UnitZ(), 0.3), gt.t};
  EXPECT_GT(mssd(off, gt, cylinder_rims(), syms), 0.0);
  EXPECT_LT(mssd(off, gt, cylinder_rims(), syms), 0.1);
  EXPECT_NEAR(mssd(off, gt, cylinder_rims(), kIdentityOnly), 20 * std::sin(0.15), 1e-3);
}

TEST(BopPoseError, AxisThroughAnOffsetTurnsAboutThatPoint) {
  // The rims turned about a z axis through (5, 0, 0) are the same rims only if the axis is
  // where the model's axis is: here the model is moved so that its axis passes there.
  std::vector<Eigen::Vector3d> moved = cylinder_rims();
  for (auto& p : moved) p.x() += 5;
  const auto syms = bop_symmetry_transforms(continuous_z({5, 0, 0}));
  const RigidPose gt{Eigen::Matrix3d::Identity(), {0, 0, 600}};
  const Eigen::Matrix3d R = about(Eigen::Vector3d::UnitZ(), 20 * 2 * std::numbers::pi / 315);
  // The estimate turns the model about the axis through (5, 0, 0): x -> R (x - o) + o.
  const RigidPose est{R, gt.t + Eigen::Vector3d(5, 0, 0) - R * Eigen::Vector3d(5, 0, 0)};
  EXPECT_NEAR(mssd(est, gt, moved, syms), 0.0, 1e-9);
  EXPECT_GT(mssd(est, gt, moved, bop_symmetry_transforms(continuous_z())), 1.0);
}

TEST(BopPoseError, DiscreteHalfTurnOfABox) {
  std::vector<Eigen::Vector3d> box;
  for (int x : {-30, 30})
    for (int y : {-10, 10})
      for (int z : {-5, 5}) box.emplace_back(x, y, z);
  PartSymmetries s;
  Eigen::Matrix4d half = Eigen::Matrix4d::Identity();
  half.topLeftCorner<3, 3>() = about(Eigen::Vector3d::UnitZ(), std::numbers::pi);
  s.discrete.push_back(half);
  const auto syms = bop_symmetry_transforms(s);
  ASSERT_EQ(syms.size(), 2u);
  const RigidPose gt{Eigen::Matrix3d::Identity(), {0, 0, 700}};
  const RigidPose est{half.topLeftCorner<3, 3>(), gt.t};
  EXPECT_NEAR(mssd(est, gt, box, syms), 0.0, 1e-9);
  EXPECT_NEAR(mssd(est, gt, box, kIdentityOnly), 2 * std::hypot(30.0, 10.0), 1e-9);
}

TEST(BopPoseError, TransformsAreTheToolkitsSet) {
  EXPECT_EQ(bop_symmetry_transforms({}).size(), 1u);
  const auto c = bop_symmetry_transforms(continuous_z({1, 2, 3}));
  ASSERT_EQ(c.size(), 315u);  // ceil(pi / 0.01), the identity first
  EXPECT_TRUE(c[0].R.isIdentity(1e-15));
  EXPECT_NEAR(c[0].t.norm(), 0.0, 1e-15);
  EXPECT_NEAR(std::atan2(c[1].R(1, 0), c[1].R(0, 0)), 2 * std::numbers::pi / 315, 1e-12);
  PartSymmetries both = continuous_z();
  both.discrete.push_back(Eigen::Matrix4d::Identity());
  both.continuous.push_back({Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()});
  EXPECT_EQ(bop_symmetry_transforms(both).size(), 2u * 2u * 315u);
  EXPECT_EQ(bop_symmetry_transforms(continuous_z(), 0.05).size(), 63u);
}

TEST(BopPoseError, ErrorsBelowTheBoundAreExactAndOthersAtLeastIt) {
  const RigidPose gt{about({1, 2, 3}, 0.7), {10, 20, 600}};
  const RigidPose est{gt.R, gt.t + Eigen::Vector3d(3, 4, 0)};
  EXPECT_NEAR(mssd(est, gt, cube(), kIdentityOnly, 5.001), 5.0, 1e-12);
  EXPECT_GE(mssd(est, gt, cube(), kIdentityOnly, 4.0), 4.0);
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  const double exact = mspd(est, gt, K, cube(), kIdentityOnly);
  EXPECT_EQ(mspd(est, gt, K, cube(), kIdentityOnly, exact * 1.001), exact);
  EXPECT_GE(mspd(est, gt, K, cube(), kIdentityOnly, exact * 0.5), exact * 0.5);
}

TEST(BopPoseError, EmptyInputIsAnInputError) {
  const RigidPose p;
  EXPECT_THROW(mssd(p, p, {}, kIdentityOnly), InputError);
  EXPECT_THROW(mssd(p, p, cube(), {}), InputError);
  EXPECT_THROW(bop_symmetry_transforms({}, 0.0), InputError);
}

}  // namespace
}  // namespace binpick::eval
