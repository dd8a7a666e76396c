// Voxel subsampling of a point cloud (kernels/voxel_subsample.cl): the model after surface
// sampling, and the scene before detection.
//
// Semantics: the cloud's bounding box is cut into cubic voxels of voxel_size starting at its
// minimum corner; every occupied voxel keeps exactly one point, the one nearest the voxel's
// centre (ties: the lowest index), with its own normal. Keeping a real point (not a mean) keeps
// true surface normals, and the choice does not depend on thread order. Survivors stay in
// input order. A thin wall narrower than a voxel keeps only one of its sides in that voxel,
// unless both faces are asked for (VoxelFaces::both, below).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/runtime/cl/cl_device.hpp"

namespace binpick {

struct VoxelSubsample {
  PointCloud cloud;                  // the kept points (and their normals, if the input had any)
  std::vector<std::uint32_t> kept;   // index in the input of each kept point, ascending
};

// The grid both implementations use (so they compute the same bits).
struct VoxelGrid {
  Eigen::Vector3f origin;   // minimum corner of the cloud
  float inv_voxel = 0;      // 1 / voxel_size as a float: the kernel multiplies by it
  std::uint32_t dims[3] = {0, 0, 0};
  std::uint64_t cells() const { return std::uint64_t(dims[0]) * dims[1] * dims[2]; }
};

// Throws InputError for a voxel_size that is not positive and finite, or a grid of more than
// 2^27 voxels (a cloud far larger than its voxels: an outlier, or a voxel size in wrong units).
VoxelGrid voxel_grid(const PointCloud& cloud, float voxel_size);

// One point per voxel (the scene), or up to two: the winner and, if any point of the voxel has
// a normal pointing away from the winner's (dot < 0), the one nearest the centre among those
// (the model: both faces of a wall thinner than a voxel; kernels/voxel_subsample.cl).
enum class VoxelFaces { one, both };

// Device routine. Throws InputError for non-finite points or normals, bad voxel size, or
// VoxelFaces::both without normals. An empty cloud gives an empty result.
VoxelSubsample voxel_subsample(ocl::Device& dev, const PointCloud& cloud, float voxel_size,
                               VoxelFaces faces = VoxelFaces::one);

// Plain C++ reference with the same result.
VoxelSubsample voxel_subsample_reference(const PointCloud& cloud, float voxel_size,
                                         VoxelFaces faces = VoxelFaces::one);

}  // namespace binpick
