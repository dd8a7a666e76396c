// Verification's inlier test reads the distance along the ray (kernels/pose_fit_shared.h,
// bp_fit_classify): with a depth sensor's noise along its rays, a right pose's faces agree in
// the same share whichever way they turn. With the point-to-plane distance, a face seen at 75
// degrees agreed almost everywhere (the noise shrunk by its cosine), and a plate seen edge on
// outscored one seen face on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "host/detect/refine/pose_fit.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct PlaneScene {
  bp_camera cam{1500.0f, 1500.0f, 128.0f, 128.0f, 1.0f, 256, 256, 0};  // 0.27 mm pixels at 400 mm
  PointCloud model;  // a 40 x 40 mm square of the model's z = 0 plane, normal +z
  FitGeometry geometry;
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  PointImage image;
};

// The square 400 mm in front of the camera, its normal turned `tilt_deg` away from the camera
// about x; every pixel's depth the plane's along its ray, plus N(0, sigma) along the ray.
PlaneScene plane_scene(double tilt_deg, double sigma, unsigned seed) {
  PlaneScene s;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) {
      s.model.points.emplace_back(float(i), float(j), 0.0f);
      s.model.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  s.geometry.diameter = 57.0f;
  s.geometry.voxel_size = 1.0f;
  s.geometry.centroid = Eigen::Vector3d::Zero();
  // Model +z faces the camera (-z in the camera's frame), then turns about x.
  s.R = Eigen::AngleAxisd(tilt_deg * kPi / 180, Eigen::Vector3d::UnitX()).toRotationMatrix() *
        Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  s.t = Eigen::Vector3d(0, 0, 400);
  const Eigen::Vector3d n = s.R * Eigen::Vector3d::UnitZ();
  s.image.width = s.cam.width;
  s.image.height = s.cam.height;
  s.image.xyzw.assign(std::size_t(s.cam.width) * s.cam.height * 4, 0.0f);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (std::uint32_t v = 0; v < s.cam.height; ++v)
    for (std::uint32_t u = 0; u < s.cam.width; ++u) {
      const Eigen::Vector3d ray((u - s.cam.cx) / s.cam.fx, (v - s.cam.cy) / s.cam.fy, 1.0);
      const double z = n.dot(s.t) / n.dot(ray) + noise(rng);
      float* p = &s.image.xyzw[(std::size_t(v) * s.cam.width + u) * 4];
      p[0] = float(ray.x() * z);
      p[1] = float(ray.y() * z);
      p[2] = float(z);
      p[3] = 1.0f;
    }
  return s;
}

// The share of the visible points that agree at the true pose, on the device and the reference.
double inlier_share(const PlaneScene& s, float tolerance) {
  const bp_pose_fit fit = make_pose_fit(s.R, s.t, s.cam, s.geometry, {4 * tolerance, tolerance, 5});
  const FitSums ref = pose_fit_sums_reference(s.image, s.cam, s.model, {fit})[0];
  auto& dev = binpick::test::test_device();
  const ocl::Buffer<float> points(dev, std::span<const float>(s.image.xyzw));
  const FitSums got = pose_fit_sums(dev, points, s.cam, upload_fit_model(dev, s.model), {fit})[0];
  for (unsigned c = 0; c < BP_FIT_CLASSES; ++c) EXPECT_EQ(got.count[c], ref.count[c]) << c;
  EXPECT_GT(ref.visible(), 500u);
  return double(ref.count[BP_FIT_INLIER]) / double(ref.visible());
}

TEST(PoseFitAlongRay, AFaceAgreesInAboutTheSameShareWhicheverWayItTurns) {
  // sigma 2 mm, tolerance 2.5 mm: 79 % of the noise lies within it along the ray. The
  // point-to-plane distance took every point of the face at 75 degrees (2.5 mm is 4.8 sigma
  // times its cosine).
  const double face_on = inlier_share(plane_scene(0, 2.0, 1), 2.5f);
  EXPECT_NEAR(face_on, 0.789, 0.04);
  for (const double tilt : {45.0, 60.0, 75.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    // Half a pixel's width times the sine widens it a little, by design (at 75 degrees 0.13 mm
    // on the 0.65 mm the tolerance allows).
    const double share = inlier_share(plane_scene(tilt, 2.0, 2), 2.5f);
    EXPECT_NEAR(share, face_on, 0.1);
    EXPECT_LT(share, 0.92);
  }
}

TEST(PoseFitAlongRay, ANoiseFreeSlopedFaceAgreesEverywhere) {
  // Exact depths along the rays: every visible point agrees, however steep the face.
  for (const double tilt : {0.0, 60.0, 78.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    EXPECT_DOUBLE_EQ(inlier_share(plane_scene(tilt, 0.0, 1), 1.5f), 1.0);
  }
}

}  // namespace
