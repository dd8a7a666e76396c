// The seen area of verification (host/detect/verify/seen_area.hpp): its arithmetic, and on images
// of the built-in plate, face up and seen at 75 degrees, that the first keeps its score and the
// second loses its lead in proportion to the area it shows.
#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <vector>

#include "host/core/error.hpp"
#include "host/detect/verify/seen_area.hpp"
#include "host/detect/verify/verify_poses.hpp"
#include "host/train/ppf_model.hpp"
#include "synth/parts/builtin_parts.hpp"
#include "tests/support/plate_scene.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

constexpr double kPi = 3.14159265358979323846;

// n unit normals spread evenly over the sphere (a Fibonacci spiral other than the test's own).
std::vector<Eigen::Vector3f> sphere_normals(int n) {
  std::vector<Eigen::Vector3f> out;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
    const double a = i * kPi * (3.0 - std::sqrt(5.0)) + 0.3;
    out.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
  }
  return out;
}

// A flat square of n x n points 2 mm apart in the model's xy plane, normals +z.
void square(int n, std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& normals) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      points.emplace_back(2.0f * float(i - n / 2), 2.0f * float(j - n / 2), 0.0f);
      normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
}

}  // namespace

TEST(SeenArea, MeanAreaIsAQuarterOfAClosedSurfacesPoints) {
  // Any closed surface's projected area is a quarter of its area on average over directions;
  // sampled evenly, a quarter of its points: a sphere, and a plate's two faces.
  const std::vector<Eigen::Vector3f> sphere = sphere_normals(3000);
  EXPECT_NEAR(mean_projected_area(sphere), 3000.0 / 4, 0.01 * 3000 / 4);
  std::vector<Eigen::Vector3f> plate(1000, Eigen::Vector3f::UnitZ());
  plate.resize(2000, -Eigen::Vector3f::UnitZ());
  EXPECT_NEAR(mean_projected_area(plate), 2000.0 / 4, 0.01 * 2000 / 4);
  EXPECT_EQ(mean_projected_area({}), 0.0);
}

TEST(SeenArea, SeenAreaWeighsVisiblePointsByTheirCosineAndMissingByHalf) {
  std::vector<Eigen::Vector3f> points, normals;
  square(21, points, normals);
  const std::size_t n = points.size();
  std::vector<std::uint8_t> classes(n, BP_FIT_INLIER);
  // Facing the camera 2 m away, then turned 75 degrees about x: its rays within 0.6 degrees of
  // the axis, so the cosine is that of the turn within 1 %.
  const Eigen::Vector3d t(0, 0, 2000);
  const Eigen::Matrix3d face = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_NEAR(seen_area(classes, face, t, points, normals), double(n), 0.001 * n);
  const Eigen::Matrix3d turned = face * Eigen::AngleAxisd(75 * kPi / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const double c75 = std::cos(75 * kPi / 180);
  EXPECT_NEAR(seen_area(classes, turned, t, points, normals), c75 * n, 0.01 * c75 * n);
  // Facing away (the identity: normals along +z, away from the camera): nothing.
  EXPECT_EQ(seen_area(classes, Eigen::Matrix3d::Identity(), t, points, normals), 0.0);
  // Every class but hidden counts; missing depth half.
  for (std::size_t i = 0; i < n; ++i) classes[i] = std::uint8_t(i % 4 == 0 ? BP_FIT_HIDDEN : i % 4 == 1 ? BP_FIT_MISSING : i % 4 == 2 ? BP_FIT_SEE_THROUGH : BP_FIT_OCCLUDED);
  std::size_t hidden = 0, missing = 0;
  for (std::size_t i = 0; i < n; ++i) hidden += i % 4 == 0, missing += i % 4 == 1;
  EXPECT_NEAR(seen_area(classes, face, t, points, normals), double(n - hidden) - 0.5 * double(missing),
              0.001 * n);
  classes.pop_back();
  EXPECT_THROW(seen_area(classes, face, t, points, normals), std::logic_error);

  EXPECT_DOUBLE_EQ(area_factor(0.4, 0.8), 0.5);
  EXPECT_DOUBLE_EQ(area_factor(2.0, 0.8), 1.0);  // at most 1
  EXPECT_DOUBLE_EQ(area_factor(0.0, 0.8), 0.0);
  EXPECT_DOUBLE_EQ(area_factor(NAN, 0.8), 0.0);
  EXPECT_DOUBLE_EQ(area_factor(0.1, 0.0), 1.0);  // off

  VerifyOptions opt;
  opt.area_scale = 11;
  EXPECT_THROW(check(opt), InputError);
  opt.area_scale = -0.1f;
  EXPECT_THROW(check(opt), InputError);
  opt.area_scale = 10;
  EXPECT_NO_THROW(check(opt));
}

TEST(SeenArea, APlateSeenAt75DegreesLosesItsLeadOverOneFaceUp) {
  auto& dev = test::test_device();
  const PpfModel model = train_ppf_model(make_builtin_part("plate"), PpfTrainParams{}, nullptr, dev);
  const bp_camera cam = test::plate_camera();
  FitGeometry g = test::plate_fit_geometry(model);
  g.points = model.fit_cloud.points;
  g.normals = model.fit_cloud.normals;
  g.mean_area = mean_projected_area(model.fit_cloud.normals);
  ASSERT_GT(g.mean_area, 0.2 * double(g.points.size()));
  const DeviceFitModel fit = upload_fit_model(dev, model.fit_cloud);

  const Eigen::Isometry3d up = test::plate_pose();  // face up, tilted 8 degrees
  Eigen::Isometry3d steep = up;  // turned 75 degrees about the plate's long axis through it
  steep.linear() = up.linear() * Eigen::AngleAxisd(75 * kPi / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  steep.translation() = up * g.centroid - steep.linear() * g.centroid;

  // Each right pose verified on its own image, the test off (scale 0) and on (0.8).
  const auto verify = [&](const Eigen::Isometry3d& pose, float scale, bool reference) {
    const PointImage image = test::plate_over_floor(cam, pose, 600.0f);
    const ocl::Buffer<float> points(dev, std::span<const float>(image.xyzw));
    VerifyOptions ro;
    ro.refine.iterations = 0;
    ro.area_scale = scale;
    const auto sums = [&](const std::vector<bp_pose_fit>& f) {
      return reference ? pose_fit_sums_reference(image, cam, model.fit_cloud, f)
                       : pose_fit_sums(dev, points, cam, fit, f);
    };
    return refine_and_verify(sums, cam, g, fit.size, {{pose.linear(), pose.translation()}}, ro)[0];
  };
  const VerifiedPose up_off = verify(up, 0, false), up_on = verify(up, 0.8f, false);
  const VerifiedPose steep_off = verify(steep, 0, false), steep_on = verify(steep, 0.8f, false);
  EXPECT_FALSE(up_off.evidence.area_tested);
  ASSERT_TRUE(up_on.evidence.area_tested && steep_on.evidence.area_tested);
  // Face up it shows one face squarely: about twice the mean (a quarter of both faces' points).
  EXPECT_GT(up_on.evidence.area_share, 1.6);
  EXPECT_LT(up_on.evidence.area_share, 2.2);
  // At 75 degrees at most a quarter as much (2 cos 75 = 0.52), less the points the fit's coarse
  // z-buffer counts behind the plate's nearer part (a cell spans several millimetres of depth
  // on so steep a face): the detector measures what it can tell is seen.
  EXPECT_GT(steep_on.evidence.area_share, 0.15);
  EXPECT_LT(steep_on.evidence.area_share, 0.6);
  // Both are right and agree alike without the test; with it the steep plate keeps its share
  // over the scale, the plate face up all of its score.
  ASSERT_GT(up_off.score(), 0.5);
  EXPECT_GT(steep_off.score(), 0.9 * up_off.score());
  EXPECT_NEAR(up_on.score(), up_off.score(), 1e-12);
  EXPECT_NEAR(steep_on.score(), steep_off.score() * steep_on.evidence.area_share / double(0.8f), 1e-12);
  EXPECT_LT(steep_on.score(), 0.8 * up_on.score());
  // The C++ reference's classes are the device's: the same share.
  EXPECT_NEAR(verify(steep, 0.8f, true).evidence.area_share, steep_on.evidence.area_share, 1e-9);
}
