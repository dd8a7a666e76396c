// Scene preparation kernels against their C++ references: the 3x3 Jacobi eigen solver,
// normals_from_points, normals_at_pixels, lowpass_depth, crop_sphere, crop_pixels,
// sample_neighbourhood and the whole prepare_scene, on random
// depth images of smooth surfaces (tilted planes, spheres) with holes and noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "host/core/error.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/bin/bin_region.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "host/detect/scene/scene_neighbourhood.hpp"
#include "host/detect/scene/scene_normals.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "kernels/scene_shared.h"
#include "tests/support/kernel_refs.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

bp_camera camera(std::uint32_t w, std::uint32_t h, float f) {
  return {f, f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0};
}

// A random scene: a tilted plane behind 0-3 spheres, ray-cast per pixel, with Gaussian depth
// noise, random single-pixel holes and a random rectangular hole.
DepthImage random_depth(std::mt19937& rng, const bp_camera& cam, float noise) {
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::normal_distribution<float> N(0.0f, noise > 0 ? noise : 1.0f);
  const Eigen::Vector3f plane_n = Eigen::Vector3f(U(rng) - 0.5f, U(rng) - 0.5f, -1.0f).normalized();
  const float plane_d = 800.0f + 400.0f * U(rng);  // plane: n . x = n . (0, 0, d)
  struct Sphere { Eigen::Vector3f c; float r; };
  std::vector<Sphere> spheres;
  for (int s = int(4 * U(rng)); s > 0; --s) {
    const float z = 500.0f + 300.0f * U(rng);
    spheres.push_back({{(U(rng) - 0.5f) * z * cam.width / cam.fx,
                        (U(rng) - 0.5f) * z * cam.height / cam.fy, z},
                       20.0f + 80.0f * U(rng)});
  }
  DepthImage img{cam.width, cam.height, std::vector<std::uint16_t>(cam.width * cam.height, 0)};
  const std::uint32_t hx = std::uint32_t(U(rng) * cam.width), hy = std::uint32_t(U(rng) * cam.height);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      if (U(rng) < 0.03f || (u >= hx && u < hx + cam.width / 8 && v >= hy && v < hy + cam.height / 8))
        continue;
      const Eigen::Vector3f d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0f);
      float t = plane_n.z() * plane_d / plane_n.dot(d);
      for (const Sphere& s : spheres) {  // |t d - c|^2 = r^2, nearest root
        const float a = d.squaredNorm(), b = d.dot(s.c), c = s.c.squaredNorm() - s.r * s.r;
        const float disc = b * b - a * c;
        if (disc >= 0) t = std::min(t, (b - std::sqrt(disc)) / a);
      }
      if (noise > 0) t += N(rng);
      if (t > 0) img.raw[v * cam.width + u] = std::uint16_t(std::lround(t / cam.depth_scale));
    }
  return img;
}

float angle_deg(const float* a, const float* b) {
  const Eigen::Vector3d x(a[0], a[1], a[2]), y(b[0], b[1], b[2]);
  return float(std::atan2(x.cross(y).norm(), x.dot(y)) * 180.0 / M_PI);
}

// Eigenvalues of the window covariance (tests/support/kernel_refs.hpp): to tell an
// ill-conditioned pixel.
Eigen::Vector3d window_eigenvalues(const PointImage& pts, int u, int v, const NormalOptions& o) {
  if (o.metric_radius == 0)
    return binpick::test::normal_window_eigenvalues(pts, u, v, o.radius, o.max_distance);
  int radius = 0, step = 1;
  bp_metric_window(pts.xyzw[4 * (std::size_t(v) * pts.width + u) + 2], o.metric_radius, o.focal,
                   &radius, &step);
  return binpick::test::normal_window_eigenvalues(pts, u, v, radius,
                                                  std::min(o.max_distance, o.metric_radius), step);
}

// Options of the parity tests: a pixel window of `radius`, or (radius < 0) a metric one of
// -radius mm.
NormalOptions normal_options(int radius, float focal) {
  NormalOptions o{std::max(radius, 0), 20.0f};
  if (radius < 0) o.metric_radius = float(-radius), o.focal = focal;
  return o;
}

}  // namespace

TEST(Jacobi3, MatchesEigenOnRandomSymmetricMatrices) {
  std::mt19937 rng(11);
  std::normal_distribution<float> N(0.0f, 1.0f);
  for (int t = 0; t < 2000; ++t) {
    Eigen::Matrix3f m;
    for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = N(rng);
    m = (m * m.transpose()).eval();
    if (t % 4 == 0) m(0, 1) = m(1, 0) = m(0, 2) = m(2, 0) = 0;  // partly diagonal
    float a[9], v[9];
    for (int i = 0; i < 9; ++i) a[i] = m(i / 3, i % 3);
    bp_sym3_jacobi(a, v);
    const Eigen::Map<const Eigen::Matrix<float, 3, 3, Eigen::RowMajor>> V(v);
    for (int k = 0; k < 3; ++k) {  // each column an eigenvector: |M v - lambda v| small
      const Eigen::Vector3f r = m * V.col(k) - a[4 * k] * V.col(k);
      ASSERT_LT(r.norm(), 1e-4f * (1 + m.norm())) << t;
      ASSERT_NEAR(V.col(k).norm(), 1.0f, 1e-5f);
    }
    Eigen::Vector3f got(a[0], a[4], a[8]);
    std::sort(got.data(), got.data() + 3);
    const Eigen::Vector3f want = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(m).eigenvalues();
    ASSERT_LT((got - want).norm(), 1e-4f * (1 + m.norm())) << t;
  }
}

TEST(Normals, MatchReferenceOnRandomImages) {
  std::mt19937 rng(1);
  int compared = 0, ill = 0;
  // Negative radii: metric windows of that many mm (about 1 to 7 pixels, or strided beyond).
  for (auto [w, h, noise, radius] : {std::tuple{1u, 1u, 0.0f, 2}, {7u, 5u, 0.5f, 1},
                                     {64u, 48u, 0.0f, 2}, {160u, 120u, 0.5f, 2},
                                     {160u, 120u, 2.0f, 3}, {160u, 120u, 0.5f, -12},
                                     {120u, 90u, 2.0f, -60}, {7u, 5u, 0.5f, -8}}) {
    const bp_camera cam = camera(w, h, 150.0f);
    const DepthImage depth = random_depth(rng, cam, noise);
    const PointImage pts = depth_to_points_reference(depth, cam);
    const NormalOptions opt = normal_options(radius, cam.fx);
    const PointImage got = normals_from_points(test_device(), pts, opt);
    const PointImage want = normals_from_points_reference(pts, opt);
    ASSERT_EQ(got.xyzw.size(), want.xyzw.size());
    for (std::uint32_t i = 0; i < w * h; ++i) {
      const float* g = &got.xyzw[4 * i];
      const float* r = &want.xyzw[4 * i];
      if (g[3] == 0 && r[3] == 0) continue;
      if (g[3] == r[3] && angle_deg(g, r) < 0.5f) {
        ++compared;
        EXPECT_NEAR(Eigen::Vector3f(g[0], g[1], g[2]).norm(), 1.0f, 1e-5f);
        EXPECT_LT(g[0] * pts.xyzw[4 * i] + g[1] * pts.xyzw[4 * i + 1] + g[2] * pts.xyzw[4 * i + 2], 0.0f);
        continue;
      }
      // A disagreement is allowed only where the problem itself is ill-conditioned.
      const Eigen::Vector3d ev = window_eigenvalues(pts, int(i % w), int(i / w), opt);
      const bool near_degenerate = ev[1] < 2.0 * BP_NORMAL_DEGENERATE_RATIO * ev[2];
      const bool close_smallest = ev[1] - ev[0] < 1e-3 * ev[2];
      EXPECT_TRUE(near_degenerate || close_smallest)
          << "pixel " << i << " valid " << g[3] << "/" << r[3] << " angle " << angle_deg(g, r)
          << " eigenvalues " << ev.transpose();
      ++ill;
    }
  }
  EXPECT_GT(compared, 20000);
  EXPECT_LT(ill, compared / 1000 + 5) << ill << " ill-conditioned of " << compared;
}

TEST(Normals, TiltedPlaneWithinOneDegreeOfTruth) {
  const bp_camera cam = camera(120, 90, 100.0f);
  const Eigen::Vector3f truth = Eigen::Vector3f(0.3f, -0.4f, -1.0f).normalized();
  DepthImage depth{cam.width, cam.height, std::vector<std::uint16_t>(cam.width * cam.height)};
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const Eigen::Vector3f d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0f);
      const float t = truth.z() * 1000.0f / truth.dot(d);
      depth.raw[v * cam.width + u] = std::uint16_t(std::lround(t / cam.depth_scale));
    }
  const PointImage normals = normals_from_points(test_device(), depth_to_points(test_device(), depth, cam), {2, 50.0f});
  float worst = 0;
  for (std::size_t i = 0; i < normals.xyzw.size() / 4; ++i) {
    ASSERT_EQ(normals.xyzw[4 * i + 3], 1.0f) << i;
    worst = std::max(worst, angle_deg(&normals.xyzw[4 * i], truth.data()));
  }
  EXPECT_LT(worst, 1.0f);
}

TEST(Normals, DoNotBleedAcrossADepthStep) {
  // Two fronto-parallel planes 30 mm apart: with a 10 mm neighbour limit every normal is -z,
  // including the pixels next to the step.
  const bp_camera cam = camera(40, 20, 100.0f);
  DepthImage depth{40, 20, std::vector<std::uint16_t>(800)};
  for (std::uint32_t i = 0; i < 800; ++i) depth.raw[i] = (i % 40) < 20 ? 5000 : 5300;
  const PointImage n = normals_from_points(test_device(), depth_to_points(test_device(), depth, cam), {2, 10.0f});
  for (std::size_t i = 0; i < 800; ++i) {
    ASSERT_EQ(n.xyzw[4 * i + 3], 1.0f) << i;
    EXPECT_NEAR(n.xyzw[4 * i + 2], -1.0f, 1e-5f) << i;
  }
}

TEST(Normals, DegenerateInputsGiveNoNormal) {
  const bp_camera cam = camera(5, 5, 100.0f);
  DepthImage depth{5, 5, std::vector<std::uint16_t>(25, 0)};
  for (float x : normals_from_points(test_device(), depth_to_points(test_device(), depth, cam)).xyzw) EXPECT_EQ(x, 0.0f);
  depth.raw[12] = 5000;  // single valid pixel
  for (float x : normals_from_points(test_device(), depth_to_points(test_device(), depth, cam)).xyzw) EXPECT_EQ(x, 0.0f);
  for (int u = 0; u < 5; ++u) depth.raw[10 + u] = 5000;  // one row: collinear points
  for (float x : normals_from_points(test_device(), depth_to_points(test_device(), depth, cam)).xyzw) EXPECT_EQ(x, 0.0f);
  EXPECT_THROW(normals_from_points(test_device(), PointImage{2, 2, std::vector<float>(3)}), InputError);
  const PointImage p = depth_to_points(test_device(), depth, cam);
  EXPECT_THROW(normals_from_points(test_device(), p, {-1, 10.0f}), InputError);
  EXPECT_THROW(normals_from_points(test_device(), p, {2, 0.0f}), InputError);
  EXPECT_THROW(normals_from_points(test_device(), p, {2, NAN}), InputError);
  EXPECT_THROW(normals_from_points(test_device(), p, {2, 10.0f, NAN, 500.0f}), InputError);
  EXPECT_THROW(normals_from_points(test_device(), p, {2, 10.0f, 5.0f, 0.0f}), InputError);
}

TEST(Lowpass, MatchesReferenceOnRandomImages) {
  std::mt19937 rng(2);
  for (auto [w, h, radius] : {std::tuple{1u, 1u, 3}, {9u, 4u, 2}, {160u, 120u, 0},
                              {160u, 120u, 5}, {200u, 50u, 11}}) {
    const bp_camera cam = camera(w, h, 150.0f);
    const PointImage pts = depth_to_points_reference(random_depth(rng, cam, 1.0f), cam);
    const std::vector<float> got = lowpass_depth(test_device(), pts, radius), want = lowpass_depth_reference(pts, radius);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      ASSERT_NEAR(got[i], want[i], 1e-5f * want[i]) << i;
      ASSERT_EQ(got[i] == 0.0f, pts.xyzw[4 * i + 3] == 0.0f) << i;  // holes stay holes
      if (radius == 0 && want[i] != 0) {
        ASSERT_EQ(got[i], pts.xyzw[4 * i + 2]);
      }
    }
  }
  EXPECT_THROW(lowpass_depth(test_device(), PointImage{1, 1, {0, 0, 1, 1}}, -1), InputError);
  EXPECT_THROW(lowpass_depth(test_device(), PointImage{1, 1, {0, 0, 1, 1}}, 65), InputError);
}

// The kernels add the same values in the same order as the reference (only additions and one
// division: nothing to contract), so they agree bit for bit, which keeps the highest points
// (an argmin over the filtered depth) the same on either side.
TEST(Lowpass, EqualsTheReferenceExactly) {
  std::mt19937 rng(21);
  for (int radius : {2, 3, 4, 5, 6, 7, 8}) {
    const bp_camera cam = camera(97 + 10 * radius, 61, 150.0f);
    const PointImage pts = depth_to_points_reference(random_depth(rng, cam, 1.0f), cam);
    EXPECT_EQ(lowpass_depth(test_device(), pts, radius), lowpass_depth_reference(pts, radius)) << radius;
  }
}

// With a mask the first pass reads it in place (lowpass_pairs_masked): bit for
// bit the reference on the mask, and the unmasked low-pass of the masked points (the points the
// mask drops set to no data), which is what the region's low-pass was before. Degenerate masks
// too: none kept (all 0), all kept (the unmasked low-pass), one pixel kept (its own depth).
TEST(Lowpass, MaskedEqualsTheLowpassOfTheMaskedPoints) {
  std::mt19937 rng(22);
  std::bernoulli_distribution keep(0.7);
  for (auto [w, h, radius] : {std::tuple{1u, 1u, 3}, {9u, 4u, 2}, {97u, 61u, 5}, {160u, 120u, 0},
                              {200u, 50u, 11}}) {
    const bp_camera cam = camera(w, h, 150.0f);
    const PointImage pts = depth_to_points_reference(random_depth(rng, cam, 1.0f), cam);
    const std::size_t n = std::size_t(w) * h;
    std::vector<std::uint8_t> random_mask(n), none(n, 0), all(n, 1), one(n, 0);
    for (auto& m : random_mask) m = keep(rng) ? 1 : 0;
    one[n / 2] = 1;
    for (const auto* mask : {&random_mask, &none, &all, &one}) {
      const std::vector<float> got = lowpass_depth(test_device(), pts, radius, mask);
      ASSERT_EQ(got, lowpass_depth_reference(pts, radius, mask)) << w << "x" << h << " r " << radius;
      ASSERT_EQ(got, lowpass_depth_reference(masked_points_reference(pts, *mask), radius));
      if (mask == &all) {
        EXPECT_EQ(got, lowpass_depth(test_device(), pts, radius));
      }
      if (mask == &none) {
        EXPECT_EQ(std::count(got.begin(), got.end(), 0.0f), std::ptrdiff_t(n));
      }
      if (mask == &one) {
        EXPECT_EQ(got[n / 2], pts.xyzw[4 * (n / 2) + 3] != 0.0f ? pts.xyzw[4 * (n / 2) + 2] : 0.0f);
      }
    }
  }
  const std::vector<std::uint8_t> short_mask(3, 1);
  EXPECT_THROW(lowpass_depth(test_device(), PointImage{2, 2, std::vector<float>(16, 1.0f)}, 1, &short_mask),
               InputError);
}

// The detector's preparation leaves the low-pass out (ScenePrepOptions::lowpass) and the region
// writes it: with no region, or a region that makes no mask, the low-pass of all points; with a
// camera-frame ROI, the low-pass of the points it keeps. Bit for bit either way.
TEST(Lowpass, LeftOutOfThePreparationTheRegionWritesIt) {
  std::mt19937 rng(23);
  const bp_camera cam = camera(120, 90, 150.0f);
  const DepthImage depth = random_depth(rng, cam, 1.0f);
  ScenePrepOptions with, without;
  with.normals_everywhere = without.normals_everywhere = false;
  without.read_back = false;
  without.lowpass = false;
  const PreparedScene full = prepare_scene(test_device(), depth, cam, with);
  ASSERT_TRUE(full.has_lowpass);
  EXPECT_EQ(full.valid_pixels, std::size_t(std::count_if(depth.raw.begin(), depth.raw.end(),
                                                        [](std::uint16_t r) { return r != 0; })));
  EXPECT_EQ(prepare_scene_reference(depth, cam, with).valid_pixels, full.valid_pixels);
  for (int roi = 0; roi < 2; ++roi) {
    PreparedScene lazy = prepare_scene(test_device(), depth, cam, without);
    EXPECT_FALSE(lazy.has_lowpass);
    for (const auto& t : lazy.timings) EXPECT_NE(t.stage, "lowpass");
    RegionSetup setup;
    if (roi) {
      RoiSpec box;
      box.lo = Eigen::Vector3d(-1e4, -1e4, -1e4);
      box.hi = Eigen::Vector3d(0, 1e4, 1e4);  // the left half of the image
      setup.roi = box;
    }
    StageTimings timings;
    const SceneRegionMask m = apply_region(lazy, setup, with.lowpass_radius, &timings);
    EXPECT_TRUE(lazy.has_lowpass);
    ASSERT_FALSE(timings.empty());
    EXPECT_EQ(timings.back().stage, "lowpass");
    const std::vector<float> got = lazy.device->filtered.read(test_device());
    if (!roi) {
      EXPECT_FALSE(m.mask.has_value());
      EXPECT_EQ(got, full.filtered_depth);
      continue;
    }
    ASSERT_TRUE(m.mask.has_value());
    const std::vector<std::uint8_t> mask = m.mask->read(test_device());
    EXPECT_GT(m.kept, 0u);
    EXPECT_LT(m.kept, mask.size() / 2 + cam.height);
    EXPECT_EQ(got, lowpass_depth_reference(masked_points_reference(full.points, mask),
                                           with.lowpass_radius));
  }
}

TEST(Crop, MatchesReferenceExactlyInPixelOrder) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  const bp_camera cam = camera(160, 120, 150.0f);
  const PointImage pts = depth_to_points_reference(random_depth(rng, cam, 0.5f), cam);
  const PointImage nrm = normals_from_points(test_device(), pts);
  for (int t = 0; t < 12; ++t) {
    const std::size_t i = std::size_t((U(rng) + 1) / 2 * (pts.xyzw.size() / 4 - 1));
    const CropOptions opt{Eigen::Vector3f(pts.xyzw[4 * i] + 50 * U(rng), pts.xyzw[4 * i + 1],
                                          pts.xyzw[4 * i + 2] + 50 * U(rng)),
                          t == 0 ? 0.0f : 200.0f * (U(rng) + 1), t % 2 == 0};
    const PointCloud got = crop_sphere(test_device(), pts, nrm, opt), want = crop_sphere_reference(pts, nrm, opt);
    ASSERT_EQ(got.points.size(), want.points.size()) << t;
    for (std::size_t k = 0; k < got.points.size(); ++k) {
      ASSERT_EQ(got.points[k], want.points[k]) << t << " " << k;
      ASSERT_EQ(got.normals[k], want.normals[k]) << t << " " << k;
    }
  }
  const PointCloud all = crop_sphere(test_device(), pts, nrm, {Eigen::Vector3f::Zero(), 1e6f, false});
  std::size_t valid = 0;
  for (std::size_t i = 0; i < pts.xyzw.size() / 4; ++i) valid += pts.xyzw[4 * i + 3] != 0;
  EXPECT_EQ(all.points.size(), valid);
  EXPECT_THROW(crop_sphere(test_device(), pts, nrm, {Eigen::Vector3f(NAN, 0, 0), 1.0f, true}), InputError);
  EXPECT_THROW(crop_sphere(test_device(), pts, nrm, {Eigen::Vector3f::Zero(), -1.0f, true}), InputError);
}

TEST(PrepareScene, MatchesReferencesAndReportsStages) {
  std::mt19937 rng(4);
  const bp_camera cam = camera(200, 150, 180.0f);
  const DepthImage depth = random_depth(rng, cam, 0.3f);
  const PreparedScene got = prepare_scene(test_device(), depth, cam);
  const PreparedScene want = prepare_scene_reference(depth, cam);
  ASSERT_TRUE(got.device);
  ASSERT_EQ(got.points.xyzw.size(), want.points.xyzw.size());
  for (std::size_t i = 0; i < got.points.xyzw.size(); ++i)
    ASSERT_NEAR(got.points.xyzw[i], want.points.xyzw[i], 1e-5f * (1 + std::fabs(want.points.xyzw[i])));
  for (std::size_t i = 0; i < got.filtered_depth.size(); ++i)
    ASSERT_NEAR(got.filtered_depth[i], want.filtered_depth[i], 1e-4f * want.filtered_depth[i]);
  int differ = 0, valid = 0;
  for (std::size_t i = 0; i < got.normals.xyzw.size() / 4; ++i) {
    valid += want.normals.xyzw[4 * i + 3] != 0;
    differ += got.normals.xyzw[4 * i + 3] != want.normals.xyzw[4 * i + 3] ||
              angle_deg(&got.normals.xyzw[4 * i], &want.normals.xyzw[4 * i]) > 0.5f;
  }
  EXPECT_GT(valid, 20000);
  EXPECT_LT(differ, valid / 1000 + 3);
  std::vector<std::string> stages;
  for (const auto& s : got.timings) {
    stages.push_back(s.stage);
    EXPECT_GE(s.ms, 0.0);
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"upload", "points", "normals", "lowpass", "readback"}));

  ScenePrepOptions device_only;
  device_only.read_back = false;
  const PreparedScene d = prepare_scene(test_device(), depth, cam, device_only);
  EXPECT_TRUE(d.points.xyzw.empty() && d.filtered_depth.empty());
  EXPECT_EQ(d.device->filtered.read(ocl::Device::shared()), got.filtered_depth);
}

TEST(PrepareScene, DegenerateImagesAndBadInput) {
  for (auto [w, h] : {std::pair{1u, 1u}, {16u, 9u}}) {
    const bp_camera cam = camera(w, h, 100.0f);
    DepthImage zero{w, h, std::vector<std::uint16_t>(w * h, 0)};
    const PreparedScene s = prepare_scene(test_device(), zero, cam);
    for (float x : s.normals.xyzw) EXPECT_EQ(x, 0.0f);
    for (float x : s.filtered_depth) EXPECT_EQ(x, 0.0f);
    zero.raw[0] = 1234;  // single valid pixel: filtered = its depth, no normal
    const PreparedScene one = prepare_scene(test_device(), zero, cam);
    EXPECT_FLOAT_EQ(one.filtered_depth[0], 123.4f);
    EXPECT_EQ(one.normals.xyzw[3], 0.0f);
  }
  const bp_camera cam = camera(4, 4, 100.0f);
  EXPECT_THROW(prepare_scene(test_device(), DepthImage{3, 4, std::vector<std::uint16_t>(12)}, cam), InputError);
  ScenePrepOptions bad;
  bad.lowpass_radius = -2;
  EXPECT_THROW(prepare_scene(test_device(), DepthImage{4, 4, std::vector<std::uint16_t>(16)}, cam, bad), InputError);
}

// The list kernel is the full-image kernel at the listed pixels: bit for bit (same function,
// same inputs), and within the full-image test's tolerance of the reference.
TEST(Normals, AtPixelsEqualTheFullImageKernel) {
  std::mt19937 rng(11);
  for (auto [w, h, noise, radius] : {std::tuple{1u, 1u, 0.0f, 2}, {7u, 5u, 0.5f, 1},
                                     {160u, 120u, 0.5f, 2}, {120u, 90u, 2.0f, 3},
                                     {64u, 48u, 0.5f, 5}, {160u, 120u, 0.5f, -15},
                                     {120u, 90u, 1.0f, -50}}) {
    const bp_camera cam = camera(w, h, 150.0f);
    const PointImage pts = depth_to_points_reference(random_depth(rng, cam, noise), cam);
    const NormalOptions opt = normal_options(radius, cam.fx);
    const PointImage full = normals_from_points(test_device(), pts, opt);
    const PointImage ref = normals_from_points_reference(pts, opt);
    std::vector<std::uint32_t> pixels;
    std::uniform_int_distribution<std::uint32_t> P(0, w * h - 1);
    for (int k = 0; k < 2000; ++k) pixels.push_back(P(rng));  // any order, repeats allowed
    const std::vector<float> got = normals_at_pixels(test_device(), pts, pixels, opt);
    const std::vector<float> want = normals_at_pixels_reference(pts, pixels, opt);
    ASSERT_EQ(got.size(), 4 * pixels.size());
    ASSERT_EQ(want.size(), 4 * pixels.size());
    int close = 0;
    for (std::size_t j = 0; j < pixels.size(); ++j) {
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(got[4 * j + c], full.xyzw[4 * pixels[j] + c]) << j << " " << c;
        ASSERT_EQ(want[4 * j + c], ref.xyzw[4 * pixels[j] + c]) << j << " " << c;
      }
      close += got[4 * j + 3] == want[4 * j + 3] &&
               (got[4 * j + 3] == 0 || angle_deg(&got[4 * j], &want[4 * j]) < 0.5f);
    }
    EXPECT_GE(close, int(pixels.size()) - int(pixels.size()) / 100 - 2);
  }
  const PointImage pts{2, 2, std::vector<float>(16, 0.0f)};
  EXPECT_TRUE(normals_at_pixels(test_device(), pts, {}).empty());
  EXPECT_THROW(normals_at_pixels(test_device(), pts, {4}), InputError);
  EXPECT_THROW(normals_at_pixels_reference(pts, {4}), InputError);
}

// The rectangle scan finds exactly the pixels the whole-image reference does, in pixel order,
// and the rectangle contains them (a sphere seen from anywhere in and around the view).
TEST(Crop, PixelsMatchReferenceExactlyInPixelOrder) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  auto& dev = ocl::Device::shared();
  for (int img = 0; img < 3; ++img) {
    const bp_camera cam = camera(200 + 40 * img, 150, 120.0f + 60.0f * img);
    const PointImage pts = depth_to_points_reference(random_depth(rng, cam, 0.5f), cam);
    ocl::Buffer<float> buf(dev, std::span<const float>(pts.xyzw), CL_MEM_READ_ONLY);
    for (int t = 0; t < 20; ++t) {
      const std::size_t i = std::size_t((U(rng) + 1) / 2 * (pts.xyzw.size() / 4 - 1));
      CropOptions opt;
      opt.centre = Eigen::Vector3f(pts.xyzw[4 * i] + 80 * U(rng), pts.xyzw[4 * i + 1] + 80 * U(rng),
                                   pts.xyzw[4 * i + 2] + 80 * U(rng));
      opt.radius = t == 0 ? 0.0f : t == 1 ? 5000.0f : 150.0f * (U(rng) + 1);
      if (t == 2) opt.centre.z() = 10.0f;  // the sphere reaches the camera plane: whole image
      const CroppedPixels got = crop_pixels(dev, buf, cam, opt);
      const CroppedPixels want = crop_pixels_reference(pts, opt);
      ASSERT_EQ(got.pixels, want.pixels) << img << " " << t;
      ASSERT_EQ(got.points, want.points) << img << " " << t;
      const auto rect = crop_pixel_rect(cam, opt);
      for (std::uint32_t p : want.pixels) {
        EXPECT_GE(p % cam.width, rect[0]);
        EXPECT_LT(p % cam.width, rect[2]);
        EXPECT_GE(p / cam.width, rect[1]);
        EXPECT_LT(p / cam.width, rect[3]);
      }
      if (t == 2) {
        EXPECT_EQ(rect, (std::array<std::uint32_t, 4>{0, 0, cam.width, cam.height}));
      }
    }
  }
}

// The detector's neighbourhood (normals only where subsampling keeps points) is exactly the old
// pipeline's: normals of the whole image, crop_sphere (points with a normal), voxel_subsample.
// Noise and holes make invalid normals, so the lazy rounds and the fallback both run.
TEST(SampleNeighbourhood, EqualsCropThenSubsampleWithNormalsEverywhere) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::size_t multi_round = 0, saved = 0;
  for (int img = 0; img < 4; ++img) {
    const bp_camera cam = camera(240, 180, 200.0f);
    const DepthImage depth = random_depth(rng, cam, img == 3 ? 4.0f : 0.5f);
    ScenePrepOptions with, without;
    with.normals.max_distance = without.normals.max_distance = img == 3 ? 3.0f : 10.0f;
    without.normals_everywhere = false;
    const PreparedScene full = prepare_scene(test_device(), depth, cam, with);
    const PreparedScene lazy = prepare_scene(test_device(), depth, cam, without);
    EXPECT_FALSE(lazy.has_normals);
    EXPECT_TRUE(lazy.normals.xyzw.empty());
    EXPECT_THROW(crop_sphere(lazy, CropOptions{}), InputError);
    for (int t = 0; t < 8; ++t) {
      const std::size_t i = std::size_t((U(rng) + 1) / 2 * (full.points.xyzw.size() / 4 - 1));
      CropOptions opt;
      opt.centre = Eigen::Vector3f(full.points.xyzw[4 * i], full.points.xyzw[4 * i + 1],
                                   full.points.xyzw[4 * i + 2] + 20 * U(rng));
      opt.radius = t == 0 ? 0.0f : 30.0f + 60.0f * (U(rng) + 1);
      const float voxel = t % 2 ? 2.6f : 6.0f;
      StageTimings timings;
      const NeighbourhoodSample got = sample_neighbourhood(lazy, opt, without.normals, voxel, &timings);
      const VoxelSubsample want = voxel_subsample(test_device(), crop_sphere(full, opt), voxel);
      ASSERT_EQ(got.cloud.points, want.cloud.points) << img << " " << t;
      ASSERT_EQ(got.cloud.normals, want.cloud.normals) << img << " " << t;
      EXPECT_EQ(got.cropped, crop_pixels_reference(full.points, opt).pixels.size());
      EXPECT_LE(got.normals, got.cropped);
      multi_round += got.rounds > 1;
      saved += got.cropped - got.normals;
      ASSERT_EQ(timings.size(), 3u);
      EXPECT_EQ(timings[0].stage, "crop");
      // And within rounding of the all-C++ reference (its normals are double Eigen's).
      const NeighbourhoodSample ref =
          sample_neighbourhood_reference(full.points, opt, without.normals, voxel);
      EXPECT_NEAR(double(ref.cloud.points.size()), double(got.cloud.points.size()),
                  2 + 0.02 * got.cloud.points.size());
    }
  }
  EXPECT_GT(multi_round, 0u);
  EXPECT_GT(saved, 0u);
}

// Patchy depth, as structured light gives on shiny parts: most pixels lost, in single pixels
// and blobs, so many a voxel's nearest point has too few neighbours for a normal. The result is
// still exactly the eager one, and the normals computed stay a small share of the crop: the
// points of a voxel whose winner has no normal are computed together, not one a round (which
// ran out of rounds and computed all of the crop: every crop here, before).
TEST(SampleNeighbourhood, PatchyDepthComputesFewNormals) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const bp_camera cam = camera(480, 360, 2000.0f);  // about half a millimetre a pixel
  DepthImage depth = random_depth(rng, cam, 0.5f);
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const bool blob = (u / 24 + v / 18) % 3 == 0 && U(rng) < 0.9f;
      if (blob || U(rng) < 0.75f) depth.raw[v * cam.width + u] = 0;
    }
  ScenePrepOptions with, without;
  with.normals.max_distance = without.normals.max_distance = 10.0f;
  without.normals_everywhere = false;
  const PreparedScene full = prepare_scene(test_device(), depth, cam, with);
  const PreparedScene lazy = prepare_scene(test_device(), depth, cam, without);
  std::size_t cropped = 0, computed = 0, invalid = 0;
  for (int t = 0; t < 6; ++t) {
    std::size_t i = 0;
    do i = std::size_t(U(rng) * float(cam.width * cam.height - 1));
    while (full.points.xyzw[4 * i + 3] == 0.0f);
    CropOptions opt;
    opt.centre = Eigen::Vector3f(full.points.xyzw[4 * i], full.points.xyzw[4 * i + 1],
                                 full.points.xyzw[4 * i + 2]);
    opt.radius = 60.0f;
    const float voxel = 6.0f;
    const NeighbourhoodSample got = sample_neighbourhood(lazy, opt, without.normals, voxel);
    const PointCloud cropped_full = crop_sphere(full, opt);
    const VoxelSubsample want = voxel_subsample(test_device(), cropped_full, voxel);
    ASSERT_EQ(got.cloud.points, want.cloud.points) << t;
    ASSERT_EQ(got.cloud.normals, want.cloud.normals) << t;
    cropped += got.cropped;
    computed += got.normals;
    invalid += got.cropped - cropped_full.points.size();
  }
  EXPECT_GT(invalid, cropped / 50);  // the depth is patchy enough to need rounds
  EXPECT_LT(computed, cropped / 4) << computed << " normals of " << cropped << " cropped";
}

// Voxels stretched along the camera's axis (noisy depth, depth_noise.hpp): the neighbourhood is
// exactly the points whose squashed copies (z / stretch) voxel subsampling keeps; on a noisy
// image it keeps fewer than cubic voxels do, the reference agrees within rounding, and a stretch
// below 1 is refused.
TEST(SampleNeighbourhood, DepthStretchKeepsThePointsOfTheSquashedCloud) {
  std::mt19937 rng(17);
  const bp_camera cam = camera(240, 180, 200.0f);
  const DepthImage depth = random_depth(rng, cam, 4.0f);
  ScenePrepOptions with, without;
  with.normals.max_distance = without.normals.max_distance = 10.0f;
  without.normals_everywhere = false;
  const PreparedScene full = prepare_scene(test_device(), depth, cam, with);
  const PreparedScene lazy = prepare_scene(test_device(), depth, cam, without);
  CropOptions opt;
  const std::size_t i = full.points.xyzw.size() / 8;  // a pixel in the middle rows
  opt.centre = Eigen::Vector3f(full.points.xyzw[4 * i], full.points.xyzw[4 * i + 1],
                               full.points.xyzw[4 * i + 2]);
  opt.radius = 90.0f;
  const float voxel = 8.0f;  // several pixels a voxel: the noise fills voxels along z
  const std::size_t cubic =
      sample_neighbourhood(lazy, opt, without.normals, voxel).cloud.points.size();
  for (float stretch : {1.5f, 2.5f}) {
    const NeighbourhoodSample got =
        sample_neighbourhood(lazy, opt, without.normals, voxel, nullptr, nullptr, stretch);
    const PointCloud cropped = crop_sphere(full, opt);
    PointCloud squashed = cropped;
    for (Eigen::Vector3f& p : squashed.points) p.z() /= stretch;
    PointCloud want;
    for (std::uint32_t k : voxel_subsample(test_device(), squashed, voxel).kept) {
      want.points.push_back(cropped.points[k]);
      want.normals.push_back(cropped.normals[k]);
    }
    ASSERT_EQ(got.cloud.points, want.points) << stretch;
    ASSERT_EQ(got.cloud.normals, want.normals) << stretch;
    EXPECT_LT(got.cloud.points.size(), cubic) << stretch;
    const NeighbourhoodSample ref =
        sample_neighbourhood_reference(full.points, opt, without.normals, voxel, nullptr, stretch);
    EXPECT_NEAR(double(ref.cloud.points.size()), double(got.cloud.points.size()),
                2 + 0.02 * got.cloud.points.size());
  }
  EXPECT_THROW(sample_neighbourhood(lazy, opt, without.normals, voxel, nullptr, nullptr, 0.5f),
               InputError);
  EXPECT_THROW(sample_neighbourhood_reference(full.points, opt, without.normals, voxel, nullptr,
                                              NAN),
               InputError);
}
