// Scene point clouds as PLY (BOP's cloud/NNNNNN.ply): vertices only, x y z and, if present,
// nx ny nz as float, in mm.
#pragma once

#include <filesystem>

#include "host/core/mesh.hpp"

namespace binpick {

// Binary little-endian PLY, written atomically.
void write_point_cloud_ply(const std::filesystem::path& path, const PointCloud& cloud);

// Any PLY the model loader reads (faces are ignored). Throws binpick::InputError naming path
// for a missing or malformed file, or a coordinate that is not finite.
PointCloud read_point_cloud_ply(const std::filesystem::path& path);

}  // namespace binpick
