// The fit model's points grouped into patches (cells of a grid in the model's frame), which the
// patch bias factor of verification tests one by one (verify/patch_bias.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"

namespace binpick {

// Each model point's patch: its cell of a grid of `size` mm in the model's frame, numbered
// 0, 1, ... in the order the points first reach them.
struct ModelPatches {
  std::vector<std::uint32_t> of_point;
  std::uint32_t count = 0;
};
ModelPatches model_patches(const PointCloud& model, float size);

}  // namespace binpick
