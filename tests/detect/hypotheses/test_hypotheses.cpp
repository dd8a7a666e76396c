// The highest-point heuristic (paper section III-C): the device rounds against the C++
// reference (the same pixels exactly), degenerate images, a ray-cast scene of spheres and a box
// whose tops must come out in order, and the unstructured-cloud variant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "host/core/error.hpp"
#include "host/detect/hypotheses/hypotheses.hpp"
#include "host/detect/hypotheses/scene_cloud.hpp"
#include "host/detect/scene/scene_lowpass.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

bp_camera camera(std::uint32_t w, std::uint32_t h, float f) {
  return {f, f, (w - 1) / 2.0f, (h - 1) / 2.0f, 0.1f, w, h, 0};
}

struct Sphere { Eigen::Vector3f c; float r; };
struct Box { Eigen::Vector3f lo, hi; };  // axis-aligned

// Ray-cast: a floor at z = 1000 under spheres and boxes; noise sigma in mm; holes are pixels
// with probability `holes` of no data.
DepthImage render(const bp_camera& cam, const std::vector<Sphere>& spheres,
                  const std::vector<Box>& boxes, std::mt19937& rng, float noise = 0.0f,
                  float holes = 0.0f) {
  std::normal_distribution<float> N(0.0f, 1.0f);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  DepthImage img{cam.width, cam.height, std::vector<std::uint16_t>(cam.width * cam.height, 0)};
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const Eigen::Vector3f d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0f);
      float t = 1000.0f;
      for (const Sphere& s : spheres) {
        const float a = d.squaredNorm(), b = d.dot(s.c), c = s.c.squaredNorm() - s.r * s.r;
        if (b * b - a * c >= 0) t = std::min(t, (b - std::sqrt(b * b - a * c)) / a);
      }
      for (const Box& b : boxes) {  // slab method
        float t0 = 0, t1 = 1e9f;
        for (int k = 0; k < 3; ++k) {
          float ta = b.lo[k] / d[k], tb = b.hi[k] / d[k];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta), t1 = std::min(t1, tb);
        }
        if (t0 <= t1) t = std::min(t, t0);
      }
      if (noise > 0) t += noise * N(rng);
      if (holes > 0 && U(rng) < holes) continue;
      img.raw[v * cam.width + u] = std::uint16_t(std::lround(t / cam.depth_scale));
    }
  return img;
}

// The points of `count` random spheres over the floor, 1 mm of noise, 5 % of the pixels lost.
PointImage random_spheres(std::mt19937& rng, const bp_camera& cam, int count) {
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::vector<Sphere> spheres;
  for (int s = 0; s < count; ++s)
    spheres.push_back({{(U(rng) - 0.5f) * 1000.0f, (U(rng) - 0.5f) * 800.0f, 800.0f + 150.0f * U(rng)},
                       15.0f + 40.0f * U(rng)});
  return depth_to_points_reference(render(cam, spheres, {}, rng, 1.0f, 0.05f), cam);
}

void expect_same(const std::vector<Hypothesis>& got, const std::vector<Hypothesis>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].pixel, want[k].pixel) << k;
    EXPECT_EQ(got[k].u, want[k].u) << k;
    EXPECT_EQ(got[k].v, want[k].v) << k;
    EXPECT_EQ(got[k].depth, want[k].depth) << k;
    EXPECT_LT((got[k].point - want[k].point).norm(), 1e-4f) << k;
  }
}

}  // namespace

TEST(Hypotheses, MatchReferenceExactlyOnRandomScenes) {
  std::mt19937 rng(1);
  for (int t = 0; t < 6; ++t) {
    const bp_camera cam = camera(120 + 40 * t, 90, 100.0f);
    const PointImage pts = random_spheres(rng, cam, 12);
    const std::vector<float> filtered = lowpass_depth_reference(pts, t % 3);
    const HypothesisOptions opt{std::uint32_t(1 + 3 * t), 40.0f + 20.0f * t};
    const auto got = find_hypotheses(test_device(), pts, filtered, opt);
    const auto want = find_hypotheses_reference(pts, filtered, opt);
    expect_same(got, want);
    EXPECT_EQ(got.size(), opt.count);
    // Each is outside the exclusion zones of the ones before it, and highest first.
    for (std::size_t k = 0; k < got.size(); ++k)
      for (std::size_t j = 0; j < k; ++j) {
        const float* p = &pts.xyzw[4 * got[k].pixel];
        EXPECT_GT((Eigen::Vector3f(p[0], p[1], p[2]) - got[j].point).norm(), opt.exclusion_radius);
        EXPECT_LE(got[j].depth, got[k].depth);
      }
  }
}

TEST(Hypotheses, TiesGoToTheSmallestPixelIndex) {
  const bp_camera cam = camera(50, 40, 100.0f);
  std::mt19937 rng(2);
  DepthImage flat = render(cam, {}, {}, rng);
  flat.raw[0] = flat.raw[1] = 0;  // the first valid pixel is 2
  const PreparedScene s = prepare_scene(test_device(), flat, cam);
  const auto h = find_hypotheses(s, {3, 5.0f});
  ASSERT_EQ(h.size(), 3u);
  EXPECT_EQ(h[0].pixel, 2u);
  expect_same(h, find_hypotheses_reference(s.points, s.filtered_depth, {3, 5.0f}));
}

TEST(Hypotheses, DegenerateImages) {
  std::mt19937 rng(3);
  for (auto [w, h] : {std::pair{1u, 1u}, {30u, 20u}}) {
    const bp_camera cam = camera(w, h, 100.0f);
    DepthImage depth{w, h, std::vector<std::uint16_t>(w * h, 0)};
    EXPECT_TRUE(find_hypotheses(prepare_scene(test_device(), depth, cam)).empty());  // all zero: none
    depth.raw[w * h - 1] = 4321;  // single valid pixel: one, then none left
    const PreparedScene one = prepare_scene(test_device(), depth, cam);
    const auto got = find_hypotheses(one, {5, 60.0f});
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].pixel, w * h - 1);
    EXPECT_FLOAT_EQ(got[0].depth, 432.1f);
    EXPECT_FLOAT_EQ(got[0].point.z(), 432.1f);
    EXPECT_TRUE(find_hypotheses(one, {0, 60.0f}).empty());  // count 0
    // A zero radius still excludes the chosen pixel: the rounds never repeat a pixel.
    depth.raw[0] = 4000;
    const auto two = find_hypotheses(prepare_scene(test_device(), depth, cam), {5, 0.0f});
    EXPECT_EQ(two.size(), w * h == 1 ? 1u : 2u);
  }
  const PointImage p{2, 1, std::vector<float>(8, 0.0f)};
  EXPECT_THROW(find_hypotheses(test_device(), p, std::vector<float>(3)), InputError);
  EXPECT_THROW(find_hypotheses(test_device(), p, std::vector<float>(2), {5, -1.0f}), InputError);
  EXPECT_THROW(find_hypotheses(test_device(), p, std::vector<float>(2), {5, NAN}), InputError);
}

TEST(Hypotheses, TopsOfTheHighestObjectsInOrder) {
  // Camera 1000 above the floor looking down; three spheres of radius 25 and a 40 mm box,
  // far enough apart that each exclusion zone (60 mm) holds one object.
  const bp_camera cam = camera(400, 300, 400.0f);
  const std::vector<Sphere> spheres{{{-200, -150, 900}, 25}, {{150, 100, 880}, 25},
                                    {{200, -150, 940}, 25}};
  const Box box{{-220, 60, 930}, {-180, 100, 1000}};  // top face at z = 930
  std::mt19937 rng(4);
  const DepthImage depth = render(cam, spheres, {box}, rng, 0.3f, 0.02f);
  ScenePrepOptions prep;
  prep.lowpass_radius = 3;
  const PreparedScene s = prepare_scene(test_device(), depth, cam, prep);
  const HypothesisOptions opt{6, 60.0f};
  const auto h = find_hypotheses(s, opt);
  ASSERT_EQ(h.size(), 6u);
  expect_same(h, find_hypotheses_reference(s.points, s.filtered_depth, opt));
  // Tops: the sphere at 880 (top z 855), at 900 (875), at 940 (915), then the box (930).
  const Eigen::Vector3f tops[] = {{150, 100, 855}, {-200, -150, 875}, {200, -150, 915}};
  for (int k = 0; k < 3; ++k) EXPECT_LT((h[k].point - tops[k]).norm(), 3.0f) << k << ": " << h[k].point.transpose();
  EXPECT_NEAR(h[3].point.z(), 930.0f, 1.0f);
  for (int k = 0; k < 2; ++k) {  // on the box's top face
    EXPECT_GT(h[3].point[k], box.lo[k] - 1);
    EXPECT_LT(h[3].point[k], box.hi[k] + 1);
  }
  // Then the floor: where it meets an object's silhouette, the low-pass mixes in the object's
  // depth, so the floor next to an object comes first (the heuristic's known behaviour).
  for (int k = 4; k < 6; ++k) EXPECT_GT(h[k].depth, 930.0f);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < k; ++j) {
      const float* p = &s.points.xyzw[4 * h[k].pixel];
      EXPECT_GT((Eigen::Vector3f(p[0], p[1], p[2]) - h[j].point).norm(), opt.exclusion_radius);
    }

  // The same scene as a cloud (--cloud): the same objects in the same order.
  PointCloud cloud;
  for (std::size_t i = 0; i < s.points.xyzw.size() / 4; ++i)
    if (s.points.xyzw[4 * i + 3] != 0)
      cloud.points.emplace_back(s.points.xyzw[4 * i], s.points.xyzw[4 * i + 1], s.points.xyzw[4 * i + 2]);
  const auto c = find_hypotheses(cloud, {opt, 4.0f, 5.0f});
  ASSERT_EQ(c.size(), 6u);
  for (int k = 0; k < 3; ++k) EXPECT_LT((c[k].point - tops[k]).norm(), 5.0f) << k;
  EXPECT_NEAR(c[3].point.z(), 930.0f, 1.0f);
}

// Highest along a bin's up (HypothesisOptions::up): the device rounds, on the whole image and
// on tiles, masked or not, against the reference (the same pixels exactly); straight down is the
// nearest-the-camera rule exactly; a bad direction is refused.
TEST(Hypotheses, AlongTheUpDirectionMatchReferenceExactly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  std::normal_distribution<float> N(0.0f, 0.3f);
  for (int t = 0; t < 4; ++t) {
    const bp_camera cam = camera(120 + 50 * t, 90 + 20 * t, 100.0f);
    const PointImage pts = random_spheres(rng, cam, 10);
    const std::vector<float> filtered = lowpass_depth_reference(pts, t % 3);
    const std::vector<std::uint8_t> mask = [&] {
      std::vector<std::uint8_t> m(filtered.size());
      for (auto& b : m) b = U(rng) < 0.8f;
      return m;
    }();
    HypothesisOptions opt{std::uint32_t(3 + 3 * t), 40.0f + 20.0f * t};
    opt.up = Eigen::Vector3f(N(rng), N(rng), -1.0f).normalized();
    for (const auto* m : {static_cast<const std::vector<std::uint8_t>*>(nullptr), &mask}) {
      const auto want = find_hypotheses_reference(pts, filtered, opt, m);
      ASSERT_EQ(want.size(), opt.count);
      expect_same(find_hypotheses(test_device(), pts, filtered, opt, m), want);
      expect_same(find_hypotheses(test_device(), pts, filtered, opt, m, &cam), want);
      // Highest first along up.
      for (std::size_t k = 1; k < want.size(); ++k)
        EXPECT_GE(opt.up->dot(want[k - 1].point), opt.up->dot(want[k].point) - 1e-3f) << k;
    }
    // Straight down: the paper's rule, pixel for pixel.
    HypothesisOptions down = opt;
    down.up = Eigen::Vector3f(0, 0, -1);
    opt.up.reset();
    expect_same(find_hypotheses(test_device(), pts, filtered, down, nullptr, &cam),
                find_hypotheses(test_device(), pts, filtered, opt, nullptr, &cam));
  }
  const PointImage p{2, 1, std::vector<float>(8, 0.0f)};
  HypothesisOptions bad{5, 10.0f};
  bad.up = Eigen::Vector3f(0, 0, -2);
  EXPECT_THROW(find_hypotheses(test_device(), p, std::vector<float>(2), bad), InputError);
  bad.up = Eigen::Vector3f(NAN, 0, 0);
  EXPECT_THROW(find_hypotheses(test_device(), p, std::vector<float>(2), bad), InputError);
}

// A camera tilted 30 degrees over a floor with a tall sphere on its far side and a small one on
// its near side: the nearest point to the camera is the near floor (the paper's rule), the
// highest along the floor's up is the tall sphere's top, then the small one's.
TEST(Hypotheses, ATiltedCameraTakesTheTopOfThePileAlongUp) {
  const bp_camera cam = camera(400, 300, 400.0f);
  const float tilt = 30.0f * float(M_PI) / 180.0f;
  const Eigen::Vector3f up(0.0f, -std::sin(tilt), -std::cos(tilt));  // towards the camera
  const float c = -up.dot(Eigen::Vector3f(0, 0, 1000));  // floor: up . p + c = 0
  const auto on_floor = [&](float x, float y) {  // the floor point under (x, y)
    return Eigen::Vector3f(x, y, -(c + up.x() * x + up.y() * y) / up.z());
  };
  const std::vector<Sphere> spheres{{on_floor(60, -150) + 40.0f * up, 40.0f},   // top 80 mm up
                                    {on_floor(-60, 150) + 12.0f * up, 12.0f}};  // top 24 mm up
  DepthImage depth{cam.width, cam.height, std::vector<std::uint16_t>(cam.width * cam.height, 0)};
  for (std::uint32_t v = 0; v < cam.height; ++v)
    for (std::uint32_t u = 0; u < cam.width; ++u) {
      const Eigen::Vector3f d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0f);
      float t = -c / up.dot(d);
      for (const Sphere& s : spheres) {
        const float a = d.squaredNorm(), b = d.dot(s.c), q = s.c.squaredNorm() - s.r * s.r;
        if (b * b - a * q >= 0) t = std::min(t, (b - std::sqrt(b * b - a * q)) / a);
      }
      depth.raw[v * cam.width + u] = std::uint16_t(std::lround(t / cam.depth_scale));
    }
  ScenePrepOptions prep;
  prep.lowpass_radius = 2;
  const PreparedScene s = prepare_scene(test_device(), depth, cam, prep);
  const auto height = [&](const Hypothesis& h) { return up.dot(h.point) + c; };
  // The exclusion (150 mm) reaches past the floor the tall sphere hides from the camera: next to
  // its silhouette the low-pass mixes the sphere's depth into the floor's and lifts the point.
  const auto nearest = find_hypotheses(test_device(), s.points, s.filtered_depth, {3, 150.0f}, nullptr, &cam);
  ASSERT_EQ(nearest.size(), 3u);
  EXPECT_LT(height(nearest[0]), 2.0f) << "the near floor";
  EXPECT_GT(nearest[0].v, cam.height * 3 / 4);
  HypothesisOptions opt{3, 150.0f};
  opt.up = up;
  const auto along = find_hypotheses(test_device(), s.points, s.filtered_depth, opt, nullptr, &cam);
  ASSERT_EQ(along.size(), 3u);
  expect_same(along, find_hypotheses_reference(s.points, s.filtered_depth, opt));
  const Eigen::Vector3f top0 = spheres[0].c + spheres[0].r * up, top1 = spheres[1].c + spheres[1].r * up;
  EXPECT_LT((along[0].point - top0).norm(), 3.0f) << along[0].point.transpose();
  EXPECT_LT((along[1].point - top1).norm(), 3.0f) << along[1].point.transpose();
  EXPECT_NEAR(height(along[0]), 80.0f, 1.0f);
}

TEST(CloudScene, NormalsCropAndBadInput) {
  PointCloud plane;  // z = 1000 + 0.5 x: normal (0.5, 0, -1) normalised, towards the camera
  for (int y = -20; y < 20; ++y)
    for (int x = -20; x < 20; ++x) plane.points.emplace_back(x * 2.0f, y * 2.0f, 1000.0f + x);
  const auto n = cloud_normals(plane, 5.0f);
  const Eigen::Vector3f truth = Eigen::Vector3f(0.5f, 0.0f, -1.0f).normalized();
  for (const auto& v : n) EXPECT_GT(v.dot(truth), std::cos(0.5f * M_PI / 180));
  plane.normals = n;
  const PointCloud crop = crop_sphere(plane, {Eigen::Vector3f(0, 0, 1000), 10.0f, true});
  EXPECT_FALSE(crop.points.empty());
  for (const auto& p : crop.points) EXPECT_LE((p - Eigen::Vector3f(0, 0, 1000)).norm(), 10.0f);
  const auto z = cloud_lowpass_z(plane, 3.0f);
  EXPECT_FLOAT_EQ(z[20 * 40 + 20], 1000.0f);  // symmetric neighbourhood of (0, 0)

  PointCloud bad = plane;
  bad.points[7].y() = NAN;
  EXPECT_THROW(find_hypotheses(bad), InputError);
  EXPECT_THROW(cloud_normals(bad, 5.0f), InputError);
  bad = plane;
  bad.normals.pop_back();
  EXPECT_THROW(check_cloud(bad), InputError);
  EXPECT_TRUE(find_hypotheses(PointCloud{}).empty());
  EXPECT_TRUE(find_hypotheses(plane, {{0, 60.0f}, 3.0f, 10.0f}).empty());
  PointCloud bare = plane;
  bare.normals.clear();
  EXPECT_THROW(crop_sphere(bare, {Eigen::Vector3f::Zero(), 1.0f, true}), InputError);
}
