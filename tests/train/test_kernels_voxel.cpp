// The four kernels of voxel subsampling (kernels/voxel_subsample.cl), each launched by itself on
// random input and compared with a plain C++ reference of that one step
// (tests/support/kernel_refs.hpp). Every output is an integer or the bits of a float computed
// with the same operations in the same order (FP_CONTRACT OFF), so all compare exactly. The
// composed routine is tests/train/test_voxel_subsample.cpp's.
#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "host/core/cloud_input.hpp"
#include "host/train/device_scan.hpp"
#include "host/train/voxel_subsample.hpp"
#include "tests/support/kernel_refs.hpp"

using namespace binpick;
using namespace binpick::test;

namespace {

constexpr u32 kCanary = 0xdeadbeefu;
constexpr std::size_t kGuard = 8;

// Random points in a cube of `extent`; with `grid`, on integer coordinates (voxel edges when the
// voxel size is 1, and many exact duplicates); every fifth point a copy of an earlier one.
std::vector<Eigen::Vector3f> random_points(std::mt19937& rng, std::size_t n, float extent,
                                           bool grid = false) {
  std::uniform_real_distribution<float> u(-extent / 2, extent / 2);
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 5 == 4) {
      out.push_back(out[std::uniform_int_distribution<std::size_t>(0, i - 1)(rng)]);
      continue;
    }
    Eigen::Vector3f p(u(rng), u(rng), u(rng));
    if (grid) p = p.array().round().matrix();
    out.push_back(p);
  }
  return out;
}

VoxelGrid grid_of(const std::vector<Eigen::Vector3f>& points, float voxel) {
  PointCloud c;
  c.points = points;
  return voxel_grid(c, voxel);
}

cl_float4 origin_of(const VoxelGrid& g) { return {{g.origin.x(), g.origin.y(), g.origin.z(), 0.0f}}; }
cl_uint4 dims_of(const VoxelGrid& g) { return {{g.dims[0], g.dims[1], g.dims[2], 0u}}; }

struct CloudCase {
  std::size_t n;
  float extent, voxel;
  bool grid;
};
const CloudCase kClouds[] = {{1, 10.0f, 1.0f, false},   {2, 10.0f, 100.0f, false},  // one cell
                             {63, 10.0f, 3.0f, false},   {1000, 20.0f, 1.0f, true},  // edges
                             {5000, 100.0f, 5.0f, false}, {20001, 52.0f, 2.6f, false},
                             {20001, 52.0f, 0.5f, false}};

// Cell indices of n points in `cells` cells, clustered in few cells so cells hold many points.
std::vector<u32> random_cells(std::mt19937& rng, std::size_t n, u32 cells) {
  std::uniform_int_distribution<u32> c(0, cells - 1), few(0, std::min(cells, 5u) - 1);
  std::vector<u32> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = i % 2 ? few(rng) : c(rng);
  return out;
}

}  // namespace

TEST(VoxelKernels, voxel_best_distance_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("voxel_subsample.cl", "voxel_best_distance");
  std::mt19937 rng(201);
  for (const CloudCase& c : kClouds) {
    const std::vector<Eigen::Vector3f> pts = random_points(rng, c.n, c.extent, c.grid);
    const VoxelGrid g = grid_of(pts, c.voxel);
    ocl::Buffer<cl_float4> points = upload(dev, pack_float4(pts));
    ocl::Buffer<u32> cell_of = guarded_buffer(dev, std::vector<u32>(c.n, kCanary), kGuard, kCanary);
    ocl::Buffer<u32> dist_bits = guarded_buffer(dev, std::vector<u32>(c.n, kCanary), kGuard, kCanary);
    ocl::Buffer<u32> best = guarded_buffer(dev, std::vector<u32>(g.cells(), kNoVoxelValue), kGuard, kCanary);
    ocl::launch(dev, k, c.n, points, u32(c.n), origin_of(g), g.inv_voxel, dims_of(g), cell_of,
                dist_bits, best);
    VoxelDistances want = voxel_best_distance_reference(pts, g);
    for (auto* v : {&want.cell_of, &want.dist_bits, &want.best_dist}) v->insert(v->end(), kGuard, kCanary);
    ASSERT_EQ(cell_of.read(dev), want.cell_of) << c.n << " " << c.voxel;
    ASSERT_EQ(dist_bits.read(dev), want.dist_bits) << c.n << " " << c.voxel;
    ASSERT_EQ(best.read(dev), want.best_dist) << c.n << " " << c.voxel;
  }
}

TEST(VoxelKernels, voxel_best_index_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("voxel_subsample.cl", "voxel_best_index");
  std::mt19937 rng(202);
  for (auto [n, cells] : {std::pair{1u, 1u}, {2u, 1u}, {100u, 7u}, {1000u, 1u}, {4097u, 300u},
                          {30000u, 20000u}}) {
    const std::vector<u32> cell_of = random_cells(rng, n, cells);
    // Distances from a handful of values: many points of a cell tie at its best distance.
    std::uniform_int_distribution<u32> d(0, 3);
    std::vector<u32> dist_bits(n);
    for (auto& b : dist_bits) b = 0x3e800000u + d(rng);  // 0.25f and its next floats
    std::vector<u32> best_dist(cells, kNoVoxelValue);
    for (u32 i = 0; i < n; ++i) best_dist[cell_of[i]] = std::min(best_dist[cell_of[i]], dist_bits[i]);
    ocl::Buffer<u32> cell_buf = upload(dev, cell_of), dist_buf = upload(dev, dist_bits),
                     best_buf = upload(dev, best_dist);
    ocl::Buffer<u32> index = guarded_buffer(dev, std::vector<u32>(cells, kNoVoxelValue), kGuard, kCanary);
    ocl::launch(dev, k, n, cell_buf, dist_buf, n, best_buf, index);
    std::vector<u32> want = voxel_best_index_reference(cell_of, dist_bits, best_dist);
    want.insert(want.end(), kGuard, kCanary);
    ASSERT_EQ(index.read(dev), want) << n << " " << cells;
  }
}

TEST(VoxelKernels, voxel_keep_flags_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("voxel_subsample.cl", "voxel_keep_flags");
  std::mt19937 rng(203);
  for (auto [n, cells] : {std::pair{1u, 1u}, {2u, 1u}, {100u, 7u}, {4097u, 300u}, {30000u, 20000u}}) {
    const std::vector<u32> cell_of = random_cells(rng, n, cells);
    // Per cell one of its points, a point of another cell, or none.
    std::vector<u32> best_index(cells, kNoVoxelValue);
    std::uniform_int_distribution<u32> any(0, n - 1), kind(0, 2);
    for (u32 i = 0; i < n; ++i)
      if (kind(rng) == 0) best_index[cell_of[i]] = i;
    for (auto& b : best_index)
      if (kind(rng) == 0) b = any(rng);
    ocl::Buffer<u32> cell_buf = upload(dev, cell_of), best_buf = upload(dev, best_index);
    ocl::Buffer<u32> keep = guarded_buffer(dev, std::vector<u32>(n, kCanary), kGuard, kCanary);
    ocl::launch(dev, k, n, cell_buf, n, best_buf, keep);
    std::vector<u32> want = voxel_keep_flags_reference(cell_of, best_index);
    want.insert(want.end(), kGuard, kCanary);
    ASSERT_EQ(keep.read(dev), want) << n << " " << cells;
  }
}

TEST(VoxelKernels, voxel_compact_matches_reference) {
  auto& dev = ocl::Device::shared();
  cl::Kernel k = dev.kernel("voxel_subsample.cl", "voxel_compact");
  std::mt19937 rng(204);
  for (auto [n, p] : {std::pair{1u, 1.0}, {1u, 0.0}, {100u, 0.5}, {1000u, 0.0}, {1000u, 1.0},
                      {30001u, 0.1}}) {
    std::bernoulli_distribution flag(p);
    std::vector<u32> keep(n);
    for (auto& f : keep) f = flag(rng) ? 1u : 0u;
    const std::vector<u32> position = exclusive_scan_reference(keep);  // n + 1 values
    const u32 total = position.back();
    ocl::Buffer<u32> keep_buf = upload(dev, keep), pos_buf = upload(dev, position);
    ocl::Buffer<u32> kept = guarded_buffer(dev, std::vector<u32>(total, kCanary), kGuard, kCanary);
    ocl::launch(dev, k, n, keep_buf, pos_buf, n, kept);
    const std::vector<u32> want =
        voxel_compact_reference(keep, position, std::vector<u32>(total + kGuard, kCanary));
    ASSERT_EQ(kept.read(dev), want) << n << " " << p;
  }
}

// The routine's sequence (host/train/voxel_subsample.cpp) step by step, each step's output
// checked against its reference on the previous step's device output; the end is the kept list
// of voxel_subsample_reference.
TEST(VoxelKernels, SequenceStepByStepGivesTheReferenceSubsample) {
  auto& dev = ocl::Device::shared();
  cl::Kernel distance = dev.kernel("voxel_subsample.cl", "voxel_best_distance");
  cl::Kernel index = dev.kernel("voxel_subsample.cl", "voxel_best_index");
  cl::Kernel flags = dev.kernel("voxel_subsample.cl", "voxel_keep_flags");
  cl::Kernel compact = dev.kernel("voxel_subsample.cl", "voxel_compact");
  std::mt19937 rng(205);
  for (const CloudCase& c : kClouds) {
    const std::vector<Eigen::Vector3f> pts = random_points(rng, c.n, c.extent, c.grid);
    const VoxelGrid g = grid_of(pts, c.voxel);
    const u32 n = u32(c.n);
    ocl::Buffer<cl_float4> points = upload(dev, pack_float4(pts));
    ocl::Buffer<u32> cell_of(dev, n), dist_bits(dev, n), keep(dev, n), position(dev, n + 1);
    ocl::Buffer<u32> best_dist(dev, g.cells()), best_index(dev, g.cells());
    best_dist.fill(dev, kNoVoxelValue);
    best_index.fill(dev, kNoVoxelValue);
    ocl::launch(dev, distance, n, points, n, origin_of(g), g.inv_voxel, dims_of(g), cell_of,
                dist_bits, best_dist);
    const VoxelDistances d = voxel_best_distance_reference(pts, g);
    ASSERT_EQ(cell_of.read(dev), d.cell_of);
    ASSERT_EQ(dist_bits.read(dev), d.dist_bits);
    ASSERT_EQ(best_dist.read(dev), d.best_dist);
    ocl::launch(dev, index, n, cell_of, dist_bits, n, best_dist, best_index);
    const std::vector<u32> bi = voxel_best_index_reference(d.cell_of, d.dist_bits, d.best_dist);
    ASSERT_EQ(best_index.read(dev), bi);
    ocl::launch(dev, flags, n, cell_of, n, best_index, keep);
    const std::vector<u32> kf = voxel_keep_flags_reference(d.cell_of, bi);
    ASSERT_EQ(keep.read(dev), kf);
    const u32 total = exclusive_scan(dev, keep, n, position);
    const std::vector<u32> pos = exclusive_scan_reference(kf);
    ASSERT_EQ(position.read(dev), pos);
    ocl::Buffer<u32> kept(dev, total);
    ocl::launch(dev, compact, n, keep, position, n, kept);
    const std::vector<u32> got = kept.read(dev);
    ASSERT_EQ(got, voxel_compact_reference(kf, pos, std::vector<u32>(total, 0)));
    PointCloud cloud;
    cloud.points = pts;
    EXPECT_EQ(got, voxel_subsample_reference(cloud, c.voxel).kept) << c.n << " " << c.voxel;
  }
}

// Degenerate input: all points coincident (every distance ties: the lowest index wins), one
// point, points on the maximum corner (clamped into the last cell), and launches in work groups
// that do not divide n (the extra work items must write nothing).
TEST(VoxelKernels, DegenerateCloudsAndPaddedWorkGroups) {
  auto& dev = ocl::Device::shared();
  cl::Kernel distance = dev.kernel("voxel_subsample.cl", "voxel_best_distance");
  cl::Kernel index = dev.kernel("voxel_subsample.cl", "voxel_best_index");
  cl::Kernel flags = dev.kernel("voxel_subsample.cl", "voxel_keep_flags");
  cl::Kernel compact = dev.kernel("voxel_subsample.cl", "voxel_compact");
  std::mt19937 rng(206);
  std::vector<std::vector<Eigen::Vector3f>> clouds;
  clouds.push_back(std::vector<Eigen::Vector3f>(77, Eigen::Vector3f(1, 2, 3)));
  clouds.push_back({Eigen::Vector3f(5, 5, 5)});
  clouds.push_back({{0, 0, 0}, {2, 2, 2}, {2, 0, 0}, {0.75f, 0.5f, 0.5f}, {0.25f, 0.5f, 0.5f}, {1.5f, 0.5f, 0.5f}});
  clouds.push_back(random_points(rng, 33, 10.0f, true));
  for (const auto& pts : clouds) {
    const VoxelGrid g = grid_of(pts, 1.0f);
    const u32 n = u32(pts.size());
    ocl::Buffer<cl_float4> points = upload(dev, pack_float4(pts));
    ocl::Buffer<u32> cell_of = guarded_buffer(dev, std::vector<u32>(n, 0), kGuard, kCanary);
    ocl::Buffer<u32> dist_bits = guarded_buffer(dev, std::vector<u32>(n, 0), kGuard, kCanary);
    ocl::Buffer<u32> keep = guarded_buffer(dev, std::vector<u32>(n, 0), kGuard, kCanary);
    ocl::Buffer<u32> best_dist = guarded_buffer(dev, std::vector<u32>(g.cells(), kNoVoxelValue), kGuard, kCanary);
    ocl::Buffer<u32> best_index = guarded_buffer(dev, std::vector<u32>(g.cells(), kNoVoxelValue), kGuard, kCanary);
    ocl::launch_local(dev, distance, n, 16, points, n, origin_of(g), g.inv_voxel, dims_of(g),
                      cell_of, dist_bits, best_dist);
    ocl::launch_local(dev, index, n, 16, cell_of, dist_bits, n, best_dist, best_index);
    ocl::launch_local(dev, flags, n, 16, cell_of, n, best_index, keep);
    VoxelDistances d = voxel_best_distance_reference(pts, g);
    std::vector<u32> bi = voxel_best_index_reference(d.cell_of, d.dist_bits, d.best_dist);
    std::vector<u32> kf = voxel_keep_flags_reference(d.cell_of, bi);
    const std::vector<u32> pos = exclusive_scan_reference(kf);
    ocl::Buffer<u32> pos_buf = upload(dev, pos);
    ocl::Buffer<u32> kept = guarded_buffer(dev, std::vector<u32>(pos.back(), kCanary), kGuard, kCanary);
    ocl::launch_local(dev, compact, n, 16, keep, pos_buf, n, kept);
    const std::vector<u32> want_kept =
        voxel_compact_reference(kf, pos, std::vector<u32>(pos.back() + kGuard, kCanary));
    for (auto* v : {&d.cell_of, &d.dist_bits, &d.best_dist, &bi, &kf}) v->insert(v->end(), kGuard, kCanary);
    EXPECT_EQ(cell_of.read(dev), d.cell_of) << n;
    EXPECT_EQ(dist_bits.read(dev), d.dist_bits) << n;
    EXPECT_EQ(best_dist.read(dev), d.best_dist) << n;
    EXPECT_EQ(best_index.read(dev), bi) << n;
    EXPECT_EQ(keep.read(dev), kf) << n;
    EXPECT_EQ(kept.read(dev), want_kept) << n;
    if (&pts == &clouds[0]) {
      EXPECT_EQ(kept.read(dev, pos.back()), std::vector<u32>{0});
    }
  }
  // The coincident cloud keeps its first point only (checked above). In the third, (2, 2, 2) on
  // the maximum corner is in the last cell, and points 3 and 4 tie in cell 0 (distance 1/16 from
  // its centre, bit for bit): point 3 wins.
  const VoxelGrid g = grid_of(clouds[2], 1.0f);
  EXPECT_EQ(g.dims[0], 3u);
  const VoxelDistances d = voxel_best_distance_reference(clouds[2], g);
  EXPECT_EQ(d.cell_of[1], 26u);
  EXPECT_EQ(d.dist_bits[3], d.dist_bits[4]);
  EXPECT_EQ(voxel_best_index_reference(d.cell_of, d.dist_bits, d.best_dist)[0], 3u);
}
