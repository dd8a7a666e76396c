// Points seen through a wall of the bin (kernels/scene_mask_shared.h, bp_seen_through_walls): a
// wire-mesh basket's walls let the sensor see the parts behind them between the bars, and a
// tilted camera sees most of its near side so. The mask keeps them out as it keeps the walls
// out. The geometry on hand-made segments and the mask kernel against its reference on random
// input (exactly: the predicate is shared); detection in a bin whose near wall is bars is
// tests/detect/test_detect_bin.cpp's.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include <Eigen/Geometry>

#include "host/core/error.hpp"
#include "host/detect/bin/scene_mask.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

// The bin frame is the camera frame (identity, origin 0): points are given in it directly.
bp_box identity_bin() {
  bp_box b{};
  b.r[0] = b.r[4] = b.r[8] = 1.0f;
  for (int a = 0; a < 3; ++a) b.lo[a] = -5000.0f, b.hi[a] = 5000.0f;
  b.active = 1;
  return b;
}

bp_walls walls_from(float cx, float cy, float cz, bp_u32 sides = 15u) {
  bp_walls w{};
  w.reach[0] = 200.0f, w.reach[1] = 150.0f;  // a 400 x 300 interior
  w.height = 180.0f;
  w.sides = sides;
  w.cam[0] = cx, w.cam[1] = cy, w.cam[2] = cz;
  return w;
}

}  // namespace

TEST(BinWalls, SegmentsThroughAWallBelowTheRim) {
  const bp_box bin = identity_bin();
  // The camera beyond the -y wall, 900 mm up: the ray to the floor 20 mm inside that wall
  // crosses its plane 38 mm up (through the wall); to the floor's centre, 225 mm up (over the
  // rim); to a point 10 mm under the rim just inside, 186 mm up (over the rim).
  const bp_walls w = walls_from(0, -600, 900);
  EXPECT_TRUE(bp_seen_through_walls(&bin, &w, 0, -130, 0));
  EXPECT_TRUE(bp_seen_through_walls(&bin, &w, -150, -120, 30));
  EXPECT_FALSE(bp_seen_through_walls(&bin, &w, 0, 0, 0));
  EXPECT_FALSE(bp_seen_through_walls(&bin, &w, 0, -140, 170));
  // The same point with the -y wall untested (the fit did not see that side).
  const bp_walls unseen = walls_from(0, -600, 900, 15u & ~8u);
  EXPECT_FALSE(bp_seen_through_walls(&bin, &unseen, 0, -130, 0));
  // Past the wall's end: the ray crosses y = -150 at x = 383, beside the 400 mm wall.
  EXPECT_FALSE(bp_seen_through_walls(&bin, &w, 400, -130, 0));
  // A point on the camera's side of the wall is not behind it.
  EXPECT_FALSE(bp_seen_through_walls(&bin, &w, 0, -170, 0));
  // The camera over the interior: nothing is seen through a wall.
  const bp_walls above = walls_from(0, 0, 900);
  EXPECT_FALSE(bp_seen_through_walls(&bin, &above, 190, 140, 0));
  EXPECT_FALSE(bp_seen_through_walls(&bin, &above, -190, -140, 0));
  // The +x wall from a camera beyond it.
  const bp_walls side = walls_from(700, 0, 900);
  EXPECT_TRUE(bp_seen_through_walls(&bin, &side, 180, 0, 0));
  EXPECT_FALSE(bp_seen_through_walls(&bin, &side, -180, 0, 0));
  // No walls to test, or no bin box: nothing is through.
  const bp_walls none = walls_from(0, -600, 900, 0u);
  EXPECT_FALSE(bp_seen_through_walls(&bin, &none, 0, -130, 0));
  bp_box off = bin;
  off.active = 0;
  EXPECT_FALSE(bp_seen_through_walls(&off, &w, 0, -130, 0));
}

// A turned bin box near random points with its walls: the kernel's mask is the reference's,
// and the walls drop points the box alone keeps.
TEST(BinWalls, MaskKernelMatchesReference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(72);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::size_t through = 0;
  for (auto [w, h, holes] : {std::tuple{1u, 1u, 0.0f}, {37u, 23u, 0.1f}, {200u, 150u, 0.3f}}) {
    const PointImage pts = random_point_image(rng, w, h, holes);
    Eigen::Vector3f mean = Eigen::Vector3f::Zero();
    int valid = 0;
    for (std::size_t i = 0; i < pts.xyzw.size() / 4; ++i)
      if (pts.xyzw[4 * i + 3] != 0)
        mean += Eigen::Vector3f(pts.xyzw[4 * i], pts.xyzw[4 * i + 1], pts.xyzw[4 * i + 2]), ++valid;
    if (valid) mean /= float(valid);
    for (int t = 0; t < 6; ++t) {
      SceneRegion region;
      RegionBox b;  // rows: the bin's axes; up turned up to 40 degrees from the optical axis
      const Eigen::Matrix3f to_cam =
          Eigen::AngleAxisf(0.7f * U(rng), Eigen::Vector3f(U(rng), U(rng), 0.2f * U(rng)).normalized())
              .toRotationMatrix() *
          Eigen::AngleAxisf(float(M_PI), Eigen::Vector3f::UnitX()).toRotationMatrix();
      b.R = to_cam.transpose();
      b.t = mean + Eigen::Vector3f(50 * U(rng), 50 * U(rng), 100.0f + 50 * U(rng));
      BinWalls walls;
      walls.reach = {150.0f + 100 * U(rng), 120.0f + 80 * U(rng)};
      walls.height = 150.0f + 100 * U(rng);
      walls.sides = t == 5 ? 0u : std::uint32_t(15 - t);
      b.lo = {-walls.reach.x(), -walls.reach.y(), -500.0f};
      b.hi = {walls.reach.x(), walls.reach.y(), 500.0f};
      region.bin = b;
      region.walls = walls;
      const std::vector<std::uint8_t> got = scene_mask(dev, pts, region);
      ASSERT_EQ(got, scene_mask_reference(pts, region)) << w << "x" << h << " case " << t;
      region.walls.reset();
      const std::vector<std::uint8_t> box_only = scene_mask_reference(pts, region);
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_LE(got[i], box_only[i]) << "the walls only take points away";
        through += box_only[i] && !got[i];
      }
      if (t == 5) {
        EXPECT_EQ(got, box_only) << "no side tested";
      }
    }
  }
  EXPECT_GT(through, 100u);
  SceneRegion bad;
  bad.bin = RegionBox{};
  bad.walls = BinWalls{};
  bad.walls->sides = 1;
  bad.walls->height = NAN;
  EXPECT_THROW(to_shared(bad), InputError);
}

