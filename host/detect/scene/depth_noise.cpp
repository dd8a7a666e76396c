#include "host/detect/scene/depth_noise.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "host/core/error.hpp"

namespace binpick {

double depth_noise_mm(DepthView depth, const bp_camera& cam) {
  if (depth.raw.size() != std::size_t(depth.width) * depth.height)
    throw InputError("depth noise: the image's size does not match its pixels");
  std::vector<double> second;
  for (std::uint32_t v = 0; v < depth.height; v += kNoiseRowStep) {
    const std::uint16_t* row = &depth.raw[std::size_t(v) * depth.width];
    for (std::uint32_t u = 1; u + 1 < depth.width; u += kNoiseColumnStep) {
      const std::uint16_t a = row[u - 1], b = row[u], c = row[u + 1];
      if (a == 0 || b == 0 || c == 0) continue;
      second.push_back(std::fabs(double(a) - 2.0 * double(b) + double(c)));
    }
  }
  if (second.size() < kMinNoiseSamples) return 0.0;
  const auto mid = second.begin() + std::ptrdiff_t(second.size() / 2);
  std::nth_element(second.begin(), mid, second.end());
  return 1.4826 * *mid / std::sqrt(6.0) * double(cam.depth_scale);
}

double scene_voxel_factor(double noise_mm, double voxel_mm, double max_factor) {
  if (!(max_factor > 1) || !(voxel_mm > 0) || !(noise_mm > 0)) return 1.0;
  const double r = noise_mm / voxel_mm;
  const double w = std::clamp((r - kNoiseVoxelStart) / (kNoiseVoxelFull - kNoiseVoxelStart), 0.0, 1.0);
  return 1.0 + w * (max_factor - 1.0);
}

}  // namespace binpick
