// Bounds-checked reading of glTF accessors: a malformed file must give an error, never a read
// outside its buffers.
#pragma once

#include <tiny_gltf.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace binpick::gltf {

// The float VEC3 elements of accessor (POSITION, NORMAL).
std::vector<Eigen::Vector3f> read_vec3(const tinygltf::Model& model, int accessor);

// The unsigned integer SCALAR elements of accessor (primitive indices).
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor);

}  // namespace binpick::gltf
