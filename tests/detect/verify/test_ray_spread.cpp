// The verification's ray spread (host/detect/verify/ray_spread.hpp): a residual along the ray is the
// point-to-plane one over the cosine; on made-up residuals, noise alone has no excess and a
// spread beyond it is the excess; the image's noise comes from a well-sampled pose; and through
// refinement: of two objects in one image, the part keeps its score and a similar object whose
// surface differs everywhere in ridges finer than a patch (so no patch is off on average) loses.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <span>

#include "host/detect/verify/verify_poses.hpp"
#include "host/core/error.hpp"
#include "host/detect/verify/ray_spread.hpp"
#include "tests/detect/refine/fit_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

std::vector<double> gaussian(std::size_t n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, sigma);
  std::vector<double> e(n);
  for (double& v : e) v = N(rng);
  return e;
}

}  // namespace

TEST(RaySpread, ResidualAlongTheRayIsThePointToPlaneOneOverTheCosine) {
  // Model points at the origin, posed 500 mm straight ahead: the ray is +z.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const double s60 = std::sqrt(3.0) / 2;
  const std::vector<Eigen::Vector3f> points(4, Eigen::Vector3f::Zero());
  const std::vector<Eigen::Vector3f> normals = {
      {0, 0, -1},                 // facing the camera: cos 1
      {float(s60), 0, -0.5f},     // turned 60 degrees: cos 0.5
      {0, 0, 1},                  // facing away: no distance along the ray
      {0, 0, -1}};                // no residual (NaN)
  const std::vector<float> residuals = {1.5f, 1.0f, 1.0f, nan};
  const auto e = ray_residuals(residuals, Eigen::Matrix3d::Identity(), {0, 0, 500}, points, normals);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0], 1.5, 1e-6);
  EXPECT_NEAR(e[1], 2.0, 1e-6);
  // A rotation of the model turns its normals with it: the second point faces the camera.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto turned = ray_residuals(residuals, turn, {0, 0, 500}, points, normals);
  ASSERT_EQ(turned.size(), 2u);
  EXPECT_NEAR(turned[1], 1.0, 1e-6);
  EXPECT_THROW(ray_residuals(std::vector<float>(3, 0.0f), Eigen::Matrix3d::Identity(),
                             {0, 0, 500}, points, normals),
               std::logic_error);
}

TEST(RaySpread, NoiseAloneHasNoExcessASpreadBeyondItIs) {
  // The image's noise: 2 mm along the rays, seen by a pose of 400 residuals.
  const RaySpread noise = ray_spread(gaussian(400, 2.0, 1));
  EXPECT_EQ(noise.n, 400u);
  EXPECT_NEAR(noise.mean_square, 4.0, 0.6);
  // Another right pose: the same noise, another sample; within two standard errors.
  for (unsigned seed = 2; seed < 12; ++seed)
    EXPECT_DOUBLE_EQ(ray_excess(ray_spread(gaussian(300, 2.0, seed)), noise), 0.0) << seed;
  // A pose on a similar object: the noise plus +-3 mm where the shapes differ, everywhere.
  std::vector<double> wrong = gaussian(300, 2.0, 3);
  for (std::size_t j = 0; j < wrong.size(); ++j) wrong[j] += (j % 2 == 0) ? 3.0 : -3.0;
  const double excess = ray_excess(ray_spread(wrong), noise);
  // sqrt(4 + 9 - 4 (1 + 2 sqrt(2 / 300 + 2 / 400))) = 2.85 with exact mean squares.
  EXPECT_GT(excess, 2.3);
  EXPECT_LT(excess, 3.4);
  EXPECT_DOUBLE_EQ(excess_factor(excess, 0.5), 0.5 / excess);
  EXPECT_DOUBLE_EQ(excess_factor(0.4, 0.5), 1.0);  // within the dead band: a right pose's leftovers
  // Nothing to compare: no excess.
  EXPECT_DOUBLE_EQ(ray_excess(ray_spread(wrong), RaySpread{}), 0.0);
  EXPECT_DOUBLE_EQ(ray_excess(RaySpread{}, noise), 0.0);
  EXPECT_EQ(ray_spread(std::vector<double>{}).n, 0u);
}

TEST(RaySpread, TheImagesNoiseIsTheLeastOfTheWellSampledPoses) {
  // A pose with 20 residuals lies low by chance more easily than one with 100.
  const std::vector<RaySpread> poses = {{4.0, 400}, {1.0, 20}, {3.0, 100}, {0.0, 0}};
  EXPECT_DOUBLE_EQ(ray_floor(poses).mean_square, 3.0);
  EXPECT_EQ(ray_floor(poses).n, 100u);
  EXPECT_DOUBLE_EQ(ray_floor(poses, 12).mean_square, 1.0);
  EXPECT_EQ(ray_floor(std::vector<RaySpread>{{1.0, 20}}).n, 0u);  // none well sampled
  EXPECT_EQ(ray_floor(std::vector<RaySpread>{}).n, 0u);
}

TEST(RaySpread, SimilarObjectWithRidgesLosesScoreTheRightPoseKeepsIt) {
  // One image: the bracket on the left; on the right an object that differs from it by +-2 mm
  // everywhere, in ridges 5 mm apart. Noise 1 mm: the tolerance widens to about 3.5 mm, so the
  // ridges are mostly inliers; patches (0.2 d, 10.8 mm) average them out.
  auto& dev = binpick::test::test_device();
  const auto ridges = [](const Eigen::Vector3f& m) {
    return 2.0 * std::sin(2 * M_PI * (m.x() + m.y() + m.z()) / 5.0);
  };
  binpick::test::FitScene part = binpick::test::make_fit_scene(1.0, 4, {}, {-45, 5, 500});
  const binpick::test::FitScene other = binpick::test::make_fit_scene(1.0, 5, ridges, {45, 5, 500});
  // Both in one depth image: the nearer surface at each pixel (the two lie apart, over the
  // floor; each pixel keeps one consistent point).
  for (std::size_t i = 0; i < part.image.xyzw.size(); i += 4)
    if (other.image.xyzw[i + 2] < part.image.xyzw[i + 2])
      std::copy_n(&other.image.xyzw[i], 4, &part.image.xyzw[i]);
  // Refinement points as dense as a trained model's (its fit cloud), as detect has them.
  part.model = voxel_subsample_reference(sample_surface(binpick::test::l_bracket(), 40000), 1.0f).cloud;
  FitGeometry& g = part.geometry;
  g.points = part.model.points;
  g.normals = part.model.normals;
  const DeviceFitModel model = upload_fit_model(dev, part.model);
  const ocl::Buffer<float> points(dev, std::span<const float>(part.image.xyzw));
  const auto sums = [&](const std::vector<bp_pose_fit>& fits) {
    return pose_fit_sums(dev, points, part.cam, model, fits);
  };
  const std::vector<PoseToRefine> poses = {{part.R, part.t}, {other.R, other.t}};
  VerifyOptions opt;
  opt.noise_factor = 3.5f;
  const auto without = refine_and_verify(sums, part.cam, g, model.size, poses, opt);
  opt.ray_band_ratio = 0.01f;
  const auto with = refine_and_verify(sums, part.cam, g, model.size, poses, opt);
  EXPECT_FALSE(without[0].evidence.ray_tested);
  ASSERT_TRUE(with[0].evidence.ray_tested);
  ASSERT_TRUE(with[1].evidence.ray_tested);
  // The part: its spread is the image's noise.
  EXPECT_DOUBLE_EQ(with[0].evidence.ray_excess, 0.0);
  EXPECT_DOUBLE_EQ(with[0].score(), without[0].score());
  // The ridges: at most sqrt(2^2 / 2) = 1.4 mm RMS; refinement fits part of them and the
  // significance margin takes some (measured: 0.85 mm), past the band of 0.54 mm.
  const double band = 0.01 * g.diameter;
  EXPECT_GT(with[1].evidence.ray_excess, 1.3 * band);
  EXPECT_LT(with[1].evidence.ray_excess, 1.5);
  EXPECT_NEAR(with[1].score() / (without[1].score() * band / with[1].evidence.ray_excess), 1.0, 1e-6);
  // Without the test the similar object scores nearly like the part (measured: 0.885 against
  // 0.930); with it, clearly lower (0.562).
  EXPECT_GT(without[1].score(), 0.9 * without[0].score());
  EXPECT_LT(with[1].score(), 0.7 * with[0].score());
  // The band is checked like the other options.
  opt.ray_band_ratio = 2.0f;
  EXPECT_THROW(check(opt), InputError);
  // Without the model's points (a geometry not set up for it) the test does not run.
  opt.ray_band_ratio = 0.01f;
  g.points.clear();
  EXPECT_FALSE(refine_and_verify(sums, part.cam, g, model.size, poses, opt)[0].evidence.ray_tested);
}
