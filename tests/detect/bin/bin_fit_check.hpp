// The bin fit on an analytic scene (bin_scene.hpp) and its check against the scene's truth,
// shared by the bin fit's tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "host/detect/bin/bin_fit.hpp"
#include "host/detect/scene/depth_noise.hpp"
#include "host/runtime/cl/cl_device.hpp"
#include "tests/detect/bin/bin_scene.hpp"

namespace binpick::test {

inline double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

inline BinFit fit(const BinScene& scene, const BinSpec& spec) {
  const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
  BinFitOptions o;
  o.spec = spec;
  o.noise = depth_noise_mm(scene.depth, scene.cam);
  return fit_bin(ocl::Device::shared(), pts.xyzw, pts.width, pts.height, o);
}

// The fit against the scene's truth: up, floor, rim height, interior size, centre and the long
// axis.
inline void expect_matches(const BinFit& b, const BinScene& scene, const BinSceneSpec& s, bool floor_plane) {
  ASSERT_TRUE(b.found) << b.why;
  SCOPED_TRACE(describe(b));
  const Eigen::Vector3d up_true = scene.bin_to_cam.col(2), x_true = scene.bin_to_cam.col(0);
  EXPECT_LT(angle_deg(b.axes.col(2), up_true), 1.0);
  // The long axis, up to its sign.
  EXPECT_LT(std::min(angle_deg(b.axes.col(0), x_true), angle_deg(b.axes.col(0), -x_true)), 1.5);
  EXPECT_NEAR(b.interior.z(), s.H, 3.0);
  EXPECT_NEAR(b.interior.x(), s.W, 6.0);
  EXPECT_NEAR(b.interior.y(), s.D, 6.0);
  const Eigen::Vector3d o = scene.to_bin(b.origin);  // the found floor centre in the true frame
  EXPECT_NEAR(o.x(), 0.0, 4.0);
  EXPECT_NEAR(o.y(), 0.0, 4.0);
  EXPECT_NEAR(o.z(), 0.0, 3.0);
  EXPECT_EQ(b.floor_plane, floor_plane);
  // Right-handed, orthonormal.
  EXPECT_NEAR((b.axes.transpose() * b.axes - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(b.axes.determinant(), 1.0, 1e-9);
}

// A heap of 500 balls on the ground with no bin (a mound, highest in the middle): the paper's
// scenes, for the tests that a slice of a heap is no rim.
inline BinSceneSpec heap_spec(unsigned seed) {
  BinSceneSpec s;
  s.H = 0.5, s.wall = 0;
  s.spheres.clear();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const double r = 12 + 18 * unit(rng), x = (unit(rng) - 0.5) * 520, y = (unit(rng) - 0.5) * 340;
    const double mound = (1 - std::pow(x / 280, 2)) * (1 - std::pow(y / 190, 2));
    s.spheres.push_back({x, y, r + 120 * mound * unit(rng), r});
  }
  return s;
}

}  // namespace binpick::test
