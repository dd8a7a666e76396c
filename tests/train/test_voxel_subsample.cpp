// Voxel subsampling (kernels/voxel_subsample.cl) and the device prefix sum it uses
// (kernels/device_scan.cl) against their C++ references; with both faces (the kernels
// voxel_opposite_side, voxel_best_index_opposite and voxel_keep_flags_faces) too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/train/device_scan.hpp"
#include "host/train/voxel_subsample.hpp"
#include "tests/support/test_device.hpp"

using namespace binpick;
using binpick::test::test_device;

namespace {

PointCloud random_cloud(std::mt19937& rng, std::size_t n, float extent, bool normals = true) {
  std::uniform_real_distribution<float> u(-extent / 2, extent / 2), c(-1, 1);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    if (normals) cloud.normals.push_back(Eigen::Vector3f(c(rng), c(rng), c(rng)).normalized());
  }
  return cloud;
}

void expect_same(const VoxelSubsample& got, const VoxelSubsample& want) {
  ASSERT_EQ(got.kept, want.kept);
  ASSERT_EQ(got.cloud.points.size(), want.cloud.points.size());
  ASSERT_EQ(got.cloud.normals.size(), want.cloud.normals.size());
  for (std::size_t i = 0; i < got.cloud.points.size(); ++i) {
    EXPECT_EQ(got.cloud.points[i], want.cloud.points[i]);
    if (!got.cloud.normals.empty()) {
      EXPECT_EQ(got.cloud.normals[i], want.cloud.normals[i]);
    }
  }
}

}  // namespace

TEST(DeviceScan, MatchesReference) {
  auto& dev = ocl::Device::shared();
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> v(0, 1000);
  for (std::size_t n : {0u, 1u, 7u, 4096u, 4097u, 100003u}) {
    std::vector<std::uint32_t> in(n);
    for (auto& x : in) x = v(rng);
    ocl::Buffer<std::uint32_t> a(dev, std::span<const std::uint32_t>(in)), b(dev, n + 1);
    const std::uint32_t total = exclusive_scan(dev, a, n, b);
    const auto want = exclusive_scan_reference(in);
    EXPECT_EQ(total, want.back()) << n;
    EXPECT_EQ(b.read(dev), want) << n;
  }
}

TEST(VoxelSubsample, MatchesReferenceOnRandomClouds) {
  std::mt19937 rng(1);
  for (auto [n, extent, voxel] : {std::tuple{1u, 10.0f, 1.0f}, {50u, 10.0f, 3.0f},
                                  {5000u, 100.0f, 5.0f}, {20000u, 52.0f, 2.6f},
                                  {20000u, 52.0f, 0.5f}}) {
    const PointCloud cloud = random_cloud(rng, n, extent, n != 50);
    const VoxelSubsample got = voxel_subsample(test_device(), cloud, voxel);
    expect_same(got, voxel_subsample_reference(cloud, voxel));
    EXPECT_GT(got.kept.size(), 0u);
    EXPECT_LE(got.kept.size(), n);
  }
}

TEST(VoxelSubsample, KeepsOnePointPerVoxelNearestItsCentre) {
  // Voxels of 1 from the minimum corner (0, 0, 0): voxel (0,0,0) holds points 0, 1, 2; point 2
  // is nearest (0.5, 0.5, 0.5). Point 3 is alone in voxel (2, 0, 0).
  PointCloud cloud;
  cloud.points = {{0, 0, 0}, {0.9f, 0.9f, 0.9f}, {0.45f, 0.5f, 0.6f}, {2.2f, 0.1f, 0.1f}};
  const VoxelSubsample got = voxel_subsample(test_device(), cloud, 1.0f);
  EXPECT_EQ(got.kept, (std::vector<std::uint32_t>{2, 3}));
  EXPECT_TRUE(got.cloud.normals.empty());
}

TEST(VoxelSubsample, CoincidentPointsKeepTheLowestIndex) {
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) {
    cloud.points.emplace_back(1, 2, 3);
    cloud.normals.emplace_back(0, 0, 1);
  }
  cloud.points.emplace_back(10, 2, 3);
  cloud.normals.emplace_back(1, 0, 0);
  const VoxelSubsample got = voxel_subsample(test_device(), cloud, 0.5f);
  EXPECT_EQ(got.kept, (std::vector<std::uint32_t>{0, 100}));
  EXPECT_EQ(got.cloud.normals[1], Eigen::Vector3f(1, 0, 0));
}

TEST(VoxelSubsample, IsDeterministic) {
  std::mt19937 rng(2);
  const PointCloud cloud = random_cloud(rng, 30000, 50.0f);
  const auto a = voxel_subsample(test_device(), cloud, 1.0f), b = voxel_subsample(test_device(), cloud, 1.0f);
  EXPECT_EQ(a.kept, b.kept);
}

TEST(VoxelSubsample, BothFacesMatchReferenceOnRandomClouds) {
  std::mt19937 rng(3);
  for (auto [n, extent, voxel] : {std::tuple{1u, 10.0f, 1.0f}, {60u, 10.0f, 3.0f},
                                  {5000u, 100.0f, 5.0f}, {20000u, 52.0f, 2.6f}}) {
    const PointCloud cloud = random_cloud(rng, n, extent);
    const VoxelSubsample got = voxel_subsample(test_device(), cloud, voxel, VoxelFaces::both);
    expect_same(got, voxel_subsample_reference(cloud, voxel, VoxelFaces::both));
    const VoxelSubsample one = voxel_subsample(test_device(), cloud, voxel);
    // Random normals: most voxels holding several points gain a second.
    EXPECT_GE(got.kept.size(), one.kept.size());
    if (n == 20000) {  // 2.5 points a voxel
      EXPECT_GT(got.kept.size(), one.kept.size() * 5 / 4);
    }
    EXPECT_TRUE(std::includes(got.kept.begin(), got.kept.end(), one.kept.begin(), one.kept.end()));
  }
  PointCloud no_normals;
  no_normals.points = {{0, 0, 0}};
  EXPECT_THROW(voxel_subsample(test_device(), no_normals, 1.0f, VoxelFaces::both), InputError);
}

TEST(VoxelSubsample, ThinSheetKeepsBothFacesOnlyWhenAsked) {
  // A 1 mm sheet in 4 mm voxels: top face up, bottom face down, in the same voxels.
  PointCloud sheet;
  for (int x = 0; x < 40; ++x)
    for (int y = 0; y < 40; ++y)
      for (float z : {0.0f, 1.0f}) {
        sheet.points.emplace_back(0.5f * x, 0.5f * y, z);
        sheet.normals.emplace_back(0.0f, 0.0f, z > 0 ? 1.0f : -1.0f);
      }
  auto faces = [](const VoxelSubsample& s) {
    int up = 0, down = 0;
    for (const auto& n : s.cloud.normals) (n.z() > 0 ? up : down)++;
    return std::pair(up, down);
  };
  const auto [up1, down1] = faces(voxel_subsample(test_device(), sheet, 4.0f));
  EXPECT_EQ(up1 + down1, 25);  // 5 x 5 voxels, one face each
  EXPECT_TRUE(up1 == 0 || down1 == 0);  // the face nearer the voxel layer's centre everywhere
  const auto [up2, down2] = faces(voxel_subsample(test_device(), sheet, 4.0f, VoxelFaces::both));
  EXPECT_EQ(up2, 25);
  EXPECT_EQ(down2, 25);
}

TEST(VoxelSubsample, EmptyAndSinglePointClouds) {
  EXPECT_TRUE(voxel_subsample(test_device(), PointCloud{}, 1.0f).kept.empty());
  PointCloud one;
  one.points = {{5, 5, 5}};
  one.normals = {{0, 1, 0}};
  const auto got = voxel_subsample(test_device(), one, 1.0f);
  EXPECT_EQ(got.kept, std::vector<std::uint32_t>{0});
  EXPECT_EQ(got.cloud.normals.size(), 1u);
}

TEST(VoxelSubsample, BadInputIsAnInputError) {
  PointCloud cloud;
  cloud.points = {{0, 0, 0}, {1, NAN, 0}};
  EXPECT_THROW(voxel_subsample(test_device(), cloud, 1.0f), InputError);
  EXPECT_THROW(voxel_subsample_reference(cloud, 1.0f), InputError);
  cloud.points[1] = {1, 1, 0};
  for (float v : {0.0f, -1.0f, NAN, INFINITY}) EXPECT_THROW(voxel_subsample(test_device(), cloud, v), InputError);
  cloud.normals = {{0, 0, 1}};  // one normal for two points
  EXPECT_THROW(voxel_subsample(test_device(), cloud, 1.0f), InputError);
  cloud.normals = {{0, 0, 1}, {0, 0, NAN}};
  EXPECT_THROW(voxel_subsample(test_device(), cloud, 1.0f), InputError);
  PointCloud far;
  far.points = {{0, 0, 0}, {1e6f, 1e6f, 1e6f}};  // 10^18 voxels
  EXPECT_THROW(voxel_subsample(test_device(), far, 1.0f), InputError);
}
