// The verification's see-through cost (VerifyOptions::through_weight, pose_refine.hpp): a
// visible model point where the sensor measured a surface farther away is free space where the
// pose puts the part. On one image of the bracket over a floor: the right pose sees through
// almost nowhere and keeps its score; a pose moved off the part over the floor sees through a
// large share of its surface and loses in proportion; the factor is exactly the documented one.
#include <gtest/gtest.h>

#include <algorithm>
#include <span>

#include "host/detect/verify/verify_poses.hpp"
#include "host/core/error.hpp"
#include "tests/detect/refine/fit_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

double denominator(const VerifiedPose& r, std::size_t model_points, const VerifyOptions& opt) {
  const double support = double(r.evidence.visible) - 0.5 * double(r.evidence.missing);
  return std::max(support, std::max(double(opt.min_support_ratio) * double(model_points), 1.0));
}

}  // namespace

TEST(SeeThrough, PoseOverFreeSpaceLosesScoreTheRightPoseKeepsIt) {
  auto& dev = binpick::test::test_device();
  // Noise 1 mm on the bracket (54 mm), the floor 40 mm behind it.
  binpick::test::FitScene s = binpick::test::make_fit_scene(1.0, 7);
  const DeviceFitModel model = upload_fit_model(dev, s.model);
  const ocl::Buffer<float> points(dev, std::span<const float>(s.image.xyzw));
  const auto sums = [&](const std::vector<bp_pose_fit>& fits) {
    return pose_fit_sums(dev, points, s.cam, model, fits);
  };
  // The right pose, and the same orientation moved sideways by 0.4 d: about half of it hangs
  // over the floor, where the sensor sees 40 mm past it.
  const Eigen::Vector3d off(0.4 * s.geometry.diameter, 0, 0);
  const std::vector<PoseToRefine> poses = {{s.R, s.t}, {s.R, s.t + off}};
  VerifyOptions opt;
  opt.noise_factor = 3.5f;
  opt.refine.iterations = 0;  // verify the poses as given: the moved one would slide back
  const auto without = refine_and_verify(sums, s.cam, s.geometry, model.size, poses, opt);
  opt.through_weight = 1.0f;
  const auto with = refine_and_verify(sums, s.cam, s.geometry, model.size, poses, opt);
  ASSERT_EQ(with.size(), 2u);
  // The counts do not depend on the weight; only the score does.
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(with[k].evidence.see_through, without[k].evidence.see_through);
    EXPECT_EQ(with[k].evidence.visible, without[k].evidence.visible);
    ASSERT_GT(without[k].score(), 0.0);
    const double factor =
        std::max(0.0, 1.0 - double(with[k].evidence.see_through) / denominator(with[k], model.size, opt));
    EXPECT_NEAR(with[k].score(), without[k].score() * factor, 1e-9);
  }
  // The right pose: the sensor sees past it at few points (noise, the silhouette's pixels).
  EXPECT_LT(with[0].evidence.see_through, 0.03 * with[0].evidence.visible);
  EXPECT_GT(with[0].score(), 0.97 * without[0].score());
  // The moved pose: much of its surface is free space.
  EXPECT_GT(with[1].evidence.see_through, 0.2 * with[1].evidence.visible);
  EXPECT_LT(with[1].score(), 0.8 * without[1].score());
  // Its lead over the moved pose grows.
  EXPECT_GT(with[0].score() - with[1].score(), without[0].score() - without[1].score());
  // Heavier weights cost more, and past the share seen through the score is 0, never negative.
  opt.through_weight = 100.0f;
  const auto heavy = refine_and_verify(sums, s.cam, s.geometry, model.size, poses, opt);
  EXPECT_DOUBLE_EQ(heavy[1].score(), 0.0);
  EXPECT_LE(heavy[0].score(), with[0].score());
  // The weight is checked like the other options.
  opt.through_weight = -1.0f;
  EXPECT_THROW(check(opt), InputError);
  opt.through_weight = 101.0f;
  EXPECT_THROW(check(opt), InputError);
}
