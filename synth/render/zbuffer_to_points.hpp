// From a perspective z-buffer to camera-frame points (paper, equation 1).
#pragma once

#include <cstdint>
#include <vector>

namespace binpick {

struct ZBufferCamera {
  std::uint32_t width = 0, height = 0;
  float fx = 0, fy = 0, cx = 0, cy = 0;
  float near_mm = 0, far_mm = 0;
};

// 4 floats a pixel: xyz in mm and w = 1 where b < 1, all 0 where the far plane shows.
// Routine: the zbuffer_to_points compute shader on the shared Vulkan device.
std::vector<float> zbuffer_to_points(const std::vector<float>& zbuffer, const ZBufferCamera& cam);
// Reference: the same in plain C++.
std::vector<float> zbuffer_to_points_reference(const std::vector<float>& zbuffer,
                                               const ZBufferCamera& cam);

}  // namespace binpick
