// Checks and packing shared by the routines that take a PointCloud: bad values are the user's
// input (InputError naming the point), and the device wants float4-aligned arrays.
#pragma once

#include <string_view>
#include <vector>

#include <CL/opencl.hpp>
#include <Eigen/Core>

#include "host/core/mesh.hpp"

namespace binpick {

// Throws InputError (prefixed with `what`) unless every point is finite and, if normals are
// required (or present), there is one finite, non-zero normal per point.
void check_point_cloud(const PointCloud& cloud, bool need_normals, std::string_view what);

// The cloud with every normal scaled to unit length (after check_point_cloud).
PointCloud with_unit_normals(const PointCloud& cloud);

// (x, y, z, 0) per vector, the layout of a float4 kernel argument.
std::vector<cl_float4> pack_float4(const std::vector<Eigen::Vector3f>& v);

}  // namespace binpick
