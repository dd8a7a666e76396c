// What reaches into the bin over its rim from outside (host/detect/bin/over_rim.hpp): the pixel
// classes (kernel over_rim_classes) against their C++ reference on random input, the flood from
// beyond a side into what is joined to it (reaching_in), the faces followed below the rim
// (follow_planes), degenerate inputs (no points, a NaN point, no bin), and the mask of an
// analytic bin with an arm over its rim.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <utility>

#include "host/core/error.hpp"
#include "host/detect/bin/bin_region.hpp"
#include "host/detect/bin/over_rim.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "tests/detect/bin/bin_scene.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

BinFit straight_bin() {
  BinFit b;
  b.found = true;
  b.axes = Eigen::Matrix3d::Identity();
  b.axes.col(1) = -Eigen::Vector3d::UnitY();
  b.axes.col(2) = -Eigen::Vector3d::UnitZ();  // up toward a camera looking down +z
  b.origin = Eigen::Vector3d(10, -5, 1000);
  b.interior = Eigen::Vector3d(400, 300, 180);
  b.tol = 3;
  return b;
}

}  // namespace

TEST(OverRimKernels, over_rim_classes_matches_reference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  for (std::uint32_t unseen : {0u, 8u, 15u}) {
    BinFit bin = straight_bin();
    bin.unseen_walls = unseen;
    const bp_over_rim g = over_rim_test(bin, 9.0);
    PointImage pts{97, 61, {}};
    pts.xyzw.resize(4 * 97 * 61);
    for (std::size_t i = 0; i < pts.xyzw.size() / 4; ++i) {
      float* p = &pts.xyzw[4 * i];
      p[0] = 300 * U(rng), p[1] = 250 * U(rng), p[2] = 820 + 200 * U(rng);
      p[3] = U(rng) < -0.6f ? 0.0f : 1.0f;  // a fifth without data
    }
    // One point exactly at the lift and at the footprint's side: neither over nor beyond.
    pts.xyzw[0] = 10 + g.reach[0], pts.xyzw[1] = -5, pts.xyzw[2] = 1000 - g.lift, pts.xyzw[3] = 1;
    // A NaN point with data: not over the rim.
    pts.xyzw[4] = pts.xyzw[5] = pts.xyzw[6] = std::nanf(""), pts.xyzw[7] = 1;
    const OverRimClasses ref = over_rim_classes_reference(pts, g);
    ocl::Buffer<float> buf(dev, std::span<const float>(pts.xyzw));
    const OverRimClasses got = over_rim_classes(dev, buf, pts.xyzw.size() / 4, g);
    // The device's count of pixels beyond a side; with none, nothing is read back. A side not
    // seen gives no seeds; with all four unseen, none at all.
    ASSERT_EQ(got.beyond, ref.beyond);
    if (unseen == 15u) {
      EXPECT_EQ(ref.beyond, 0u);
      EXPECT_TRUE(got.classes.empty() && got.heights.empty());
      continue;
    }
    EXPECT_GT(ref.beyond, 0u);
    ASSERT_EQ(got.classes, ref.classes);
    ASSERT_EQ(got.heights.size(), ref.heights.size());
    for (std::size_t i = 0; i < ref.heights.size(); ++i) {
      if (!(std::isnan(got.heights[i]) && std::isnan(ref.heights[i]))) {
        ASSERT_EQ(std::memcmp(&got.heights[i], &ref.heights[i], 4), 0) << i;
      }
    }
    EXPECT_EQ(ref.classes[0], BP_OVER_RIM_NO);
    EXPECT_EQ(ref.classes[1], BP_OVER_RIM_NO);
    int seen[4] = {};
    for (const std::uint8_t c : ref.classes) ++seen[c];
    EXPECT_GT(seen[BP_OVER_RIM_NO], 0);
    EXPECT_GT(seen[BP_OVER_RIM_IN], 0);
    EXPECT_GT(seen[BP_OVER_RIM_NODATA], 0);
    EXPECT_EQ(std::size_t(seen[BP_OVER_RIM_OUT]), ref.beyond);
  }
  // No points, and a bin not found.
  EXPECT_TRUE(over_rim_classes(dev, ocl::Buffer<float>(dev, 4), 0, over_rim_test(straight_bin(), 9))
                  .classes.empty());
  EXPECT_THROW(over_rim_test(BinFit{}, 9), InputError);
}

// On a line of pixels: a seed, a stretch over the footprint joined to it across a hole of 3
// pixels, then a step up larger than max_step, then more over the footprint; an island apart.
TEST(ReachingIn, FollowsWhatIsJoinedAcrossHolesAndStopsAtSteps) {
  const std::uint32_t w = 20, h = 3;
  OverRimClasses c{std::vector<std::uint8_t>(w * h, BP_OVER_RIM_NO), std::vector<float>(w * h, 0)};
  auto set = [&](std::uint32_t u, std::uint8_t cls, float z) {
    c.classes[w + u] = cls, c.heights[w + u] = z;
  };
  set(0, BP_OVER_RIM_OUT, 250);
  set(1, BP_OVER_RIM_IN, 248);
  for (std::uint32_t u = 2; u < 5; ++u) set(u, BP_OVER_RIM_NODATA, 0);
  set(5, BP_OVER_RIM_IN, 246);
  set(6, BP_OVER_RIM_IN, 244);
  set(7, BP_OVER_RIM_IN, 300);  // a step of 56 mm
  set(8, BP_OVER_RIM_IN, 301);
  set(15, BP_OVER_RIM_IN, 246);  // an island
  const std::vector<std::uint8_t> r = reaching_in(c, w, h, 10.0f, 3);
  for (std::uint32_t u : {0u, 1u, 5u, 6u}) EXPECT_EQ(r[w + u], 1) << u;
  for (std::uint32_t u : {2u, 7u, 8u, 15u}) EXPECT_EQ(r[w + u], 0) << u;
  EXPECT_EQ(r[5], 0);  // the row above is not over the rim
  // A hole one pixel longer than max_gap stops it.
  const std::vector<std::uint8_t> short_gap = reaching_in(c, w, h, 10.0f, 2);
  EXPECT_EQ(short_gap[w + 1], 1);
  EXPECT_EQ(short_gap[w + 5], 0);
  // Nothing beyond a side: nothing reached; sizes that do not match are refused.
  c.classes[w] = BP_OVER_RIM_IN;
  const std::vector<std::uint8_t> none = reaching_in(c, w, h, 10.0f, 3);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
  EXPECT_THROW(reaching_in(c, w + 1, h, 10.0f, 3), InputError);
}

// A face going on below the rim (a plane z = 900 + 0.5 x, camera frame) is followed from the
// reached pixels on it across a hole, not onto a point 20 mm off it.
TEST(FollowPlanes, FollowsAFaceAndNothingOffIt) {
  const std::uint32_t w = 30, h = 10;
  std::vector<float> xyzw(4 * w * h);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      float* p = &xyzw[4 * (v * w + u)];
      p[0] = float(u) * 4, p[1] = float(v) * 4, p[2] = 900 + 0.5f * p[0], p[3] = 1;
    }
  for (std::uint32_t v = 0; v < h; ++v) xyzw[4 * (v * w + 12) + 3] = 0;  // a hole across
  xyzw[4 * (5 * w + 20) + 2] += 20;  // off the face
  std::vector<std::uint8_t> reached(w * h, 0);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < 3; ++u) reached[v * w + u] = 1;
  FoundPlane pl;
  pl.normal = Eigen::Vector3d(0.5, 0, -1).normalized();
  pl.d = 900 / std::sqrt(1.25);
  std::vector<std::uint8_t> r = reached;
  follow_planes(xyzw, w, h, {pl}, 2.0f, 1, r);
  EXPECT_EQ(r[5 * w + 25], 1);
  EXPECT_EQ(r[5 * w + 20], 0);
  EXPECT_EQ(r[5 * w + 12], 0);  // no data: nothing to mask
  // Without planes nothing grows.
  std::vector<std::uint8_t> same = reached;
  follow_planes(xyzw, w, h, {}, 2.0f, 1, same);
  EXPECT_EQ(same, reached);
  EXPECT_THROW(follow_planes(xyzw, w, h + 1, {pl}, 2.0f, 1, same), InputError);
}

// An arm over the -y wall, its top 60 mm over the rim and 80 mm into the interior: straight down
// and tilted 30 degrees, no pixel on it is kept, every part (sphere) still is. With the arm kept
// in (keep_over_rim), some of it is: the test can fail.
TEST(OverRim, AnArmOverTheRimIsKeptOutAndThePartsStay) {
  auto& dev = ocl::Device::shared();
  for (double tilt : {0.0, 30.0}) {
    SCOPED_TRACE(testing::Message() << "tilt " << tilt);
    BinSceneSpec s;
    s.tilt_deg = tilt;
    s.boxes.push_back({{-60, -s.D / 2 - 1500, s.H + 20}, {60, -s.D / 2 + 80, s.H + 60}});
    const BinScene scene = make_bin_scene(s);
    const PointImage pts = depth_to_points_reference(scene.depth, scene.cam);
    ScenePrepOptions po;
    po.normals_everywhere = false;
    po.read_back = false;
    const auto kept_on_arm = [&](bool keep) {
      PreparedScene prepared = prepare_scene(dev, scene.depth, scene.cam, po);
      RegionSetup setup;
      setup.bin.mode = BinSpec::Mode::find;
      setup.margin = 6;
      setup.above = 100;
      setup.keep_over_rim = keep;
      setup.over_rim_gap = 40;
      const SceneRegionMask m = apply_region(prepared, setup, po.lowpass_radius);
      EXPECT_TRUE(m.mask.has_value()) << m.warning;
      if (!m.mask) return std::pair<int, int>{-1, -1};
      const std::vector<std::uint8_t> mask = m.mask->read(dev);
      int arm = 0, parts = 0;
      for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const Eigen::Vector3d q = scene.to_bin(
            Eigen::Vector3d(pts.xyzw[4 * i], pts.xyzw[4 * i + 1], pts.xyzw[4 * i + 2]));
        arm += q.z() > s.H + 15 && std::abs(q.x()) < 62;
        for (const Eigen::Vector4d& b : s.spheres)
          parts += (q - b.head<3>()).norm() < b[3] + 1;
      }
      return std::pair<int, int>{arm, parts};
    };
    const auto [arm_in, parts_in] = kept_on_arm(true);
    const auto [arm_out, parts_out] = kept_on_arm(false);
    EXPECT_GT(arm_in, 50) << "the premise: the arm is kept without the test";
    EXPECT_EQ(arm_out, 0);
    EXPECT_EQ(parts_out, parts_in);
    EXPECT_GT(parts_out, 100);
  }
}
