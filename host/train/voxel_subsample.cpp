#include "host/train/voxel_subsample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/core/cloud_input.hpp"
#include "host/train/device_scan.hpp"

namespace binpick {
namespace {

constexpr std::uint64_t kMaxVoxelCells = 1ull << 27;

void check(const PointCloud& cloud, float voxel_size) {
  if (!(voxel_size > 0 && std::isfinite(voxel_size)))
    throw InputError("voxel subsampling: voxel size " + std::to_string(voxel_size) +
                     " must be positive and finite");
  if (cloud.points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InputError("voxel subsampling: more than 2^32 points");
  check_point_cloud(cloud, false, "voxel subsampling");
}

VoxelSubsample gather(const PointCloud& cloud, std::vector<std::uint32_t> kept) {
  VoxelSubsample out;
  out.cloud.points.reserve(kept.size());
  for (std::uint32_t i : kept) out.cloud.points.push_back(cloud.points[i]);
  if (!cloud.normals.empty())
    for (std::uint32_t i : kept) out.cloud.normals.push_back(cloud.normals[i]);
  out.kept = std::move(kept);
  return out;
}

void check_faces(const PointCloud& cloud, VoxelFaces faces) {
  if (faces == VoxelFaces::both && cloud.normals.size() != cloud.points.size())
    throw InputError("voxel subsampling of both faces needs a normal per point");
}

}  // namespace

VoxelGrid voxel_grid(const PointCloud& cloud, float voxel_size) {
  check(cloud, voxel_size);
  VoxelGrid g;
  g.inv_voxel = 1.0f / voxel_size;
  if (cloud.points.empty()) {
    g.origin.setZero();
    return g;
  }
  Eigen::Vector3f lo = cloud.points[0], hi = cloud.points[0];
  for (const auto& p : cloud.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  g.origin = lo;
  double cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double d = std::floor(double((hi[a] - lo[a]) * g.inv_voxel)) + 1;
    cells *= d;
    if (cells > double(kMaxVoxelCells))
      throw InputError("voxel subsampling: a cloud of extent " +
                       std::to_string((hi - lo).maxCoeff()) + " at voxel size " +
                       std::to_string(voxel_size) + " spans more than 2^27 voxels (outliers? "
                       "wrong units?)");
    g.dims[a] = static_cast<std::uint32_t>(d);
  }
  return g;
}

VoxelSubsample voxel_subsample(ocl::Device& dev, const PointCloud& cloud, float voxel_size,
                               VoxelFaces faces) {
  const VoxelGrid g = voxel_grid(cloud, voxel_size);
  check_faces(cloud, faces);
  const std::size_t n = cloud.points.size();
  if (n == 0) return gather(cloud, {});
  const auto count = static_cast<std::uint32_t>(n);
  const bool both = faces == VoxelFaces::both;
  ocl::Buffer<cl_float4> points(dev, std::span<const cl_float4>(pack_float4(cloud.points)),
                                CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> cell_of(dev, n), dist_bits(dev, n), keep(dev, n), position(dev, n + 1);
  const std::size_t slots = (both ? 2 : 1) * g.cells();
  ocl::Buffer<std::uint32_t> best_dist(dev, slots), best_index(dev, slots);
  best_dist.fill(dev, 0xffffffffu);
  best_index.fill(dev, 0xffffffffu);
  const cl_float4 origin{{g.origin.x(), g.origin.y(), g.origin.z(), 0.0f}};
  const cl_uint4 dims{{g.dims[0], g.dims[1], g.dims[2], 0u}};

  cl::Kernel distance = dev.kernel("voxel_subsample.cl", "voxel_best_distance");
  cl::Kernel index = dev.kernel("voxel_subsample.cl", "voxel_best_index");
  cl::Kernel flags = dev.kernel("voxel_subsample.cl", "voxel_keep_flags");
  cl::Kernel compact = dev.kernel("voxel_subsample.cl", "voxel_compact");
  ocl::launch(dev, distance, n, points, count, origin, g.inv_voxel, dims, cell_of, dist_bits,
              best_dist);
  ocl::launch(dev, index, n, cell_of, dist_bits, count, best_dist, best_index);
  if (both) {
    const auto cells = static_cast<std::uint32_t>(g.cells());
    ocl::Buffer<cl_float4> normals(dev, std::span<const cl_float4>(pack_float4(cloud.normals)),
                                   CL_MEM_READ_ONLY);
    ocl::Buffer<std::uint32_t> cell2_of(dev, n);
    cl::Kernel side = dev.kernel("voxel_subsample.cl", "voxel_opposite_side");
    cl::Kernel index2 = dev.kernel("voxel_subsample.cl", "voxel_best_index_opposite");
    cl::Kernel flags2 = dev.kernel("voxel_subsample.cl", "voxel_keep_flags_faces");
    ocl::launch(dev, side, n, normals, cell_of, count, cells, best_index, cell2_of, best_dist,
                dist_bits);
    ocl::launch(dev, index2, n, cell2_of, dist_bits, count, best_dist, best_index);
    ocl::launch(dev, flags2, n, cell_of, count, cells, best_index, keep);
  } else {
    ocl::launch(dev, flags, n, cell_of, count, best_index, keep);
  }
  const std::uint32_t kept_count = exclusive_scan(dev, keep, n, position);
  ocl::Buffer<std::uint32_t> kept(dev, kept_count);
  ocl::launch(dev, compact, n, keep, position, count, kept);
  return gather(cloud, kept.read(dev));
}

VoxelSubsample voxel_subsample_reference(const PointCloud& cloud, float voxel_size,
                                         VoxelFaces faces) {
  const VoxelGrid g = voxel_grid(cloud, voxel_size);
  check_faces(cloud, faces);
  // cell -> (distance squared in voxel units, index): the smallest pair wins.
  std::map<std::uint64_t, std::pair<float, std::uint32_t>> best;
  std::vector<std::pair<std::uint64_t, float>> cell_dist(cloud.points.size());
  for (std::uint32_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f f = (cloud.points[i] - g.origin) * g.inv_voxel;
    std::uint64_t c[3];
    float dist2 = 0;
    for (int a = 0; a < 3; ++a) {
      c[a] = std::min<std::uint64_t>(static_cast<std::uint64_t>(std::floor(f[a])), g.dims[a] - 1);
      const float d = f[a] - (float(c[a]) + 0.5f);
      dist2 = a == 0 ? d * d : dist2 + d * d;
    }
    const std::uint64_t cell = (c[2] * g.dims[1] + c[1]) * g.dims[0] + c[0];
    cell_dist[i] = {cell, dist2};
    auto [it, inserted] = best.try_emplace(cell, dist2, i);
    if (!inserted && std::pair(dist2, i) < it->second) it->second = {dist2, i};
  }
  std::vector<std::uint32_t> kept;
  for (const auto& [cell, b] : best) kept.push_back(b.second);
  if (faces == VoxelFaces::both) {
    // The second round: among points facing away from their voxel's winner.
    std::map<std::uint64_t, std::pair<float, std::uint32_t>> opposite;
    for (std::uint32_t i = 0; i < cloud.points.size(); ++i) {
      const auto [cell, dist2] = cell_dist[i];
      const Eigen::Vector3f& a = cloud.normals[i];
      const Eigen::Vector3f& b = cloud.normals[best.at(cell).second];
      // The kernel's float expression, term by term.
      const float dot = a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
      if (!(dot < 0.0f)) continue;
      auto [it, inserted] = opposite.try_emplace(cell, dist2, i);
      if (!inserted && std::pair(dist2, i) < it->second) it->second = {dist2, i};
    }
    for (const auto& [cell, b] : opposite) kept.push_back(b.second);
  }
  std::sort(kept.begin(), kept.end());
  return gather(cloud, std::move(kept));
}

}  // namespace binpick
