// Depth images as the BOP toolkit compares them: it reads a depth PNG as float32 and multiplies
// it by depth_scale in float32 (inout.load_depth), and turns depth (z along the optical axis)
// into the distance from the camera centre (misc.depth_im_to_dist_im_fast) before any test.
// Same arithmetic, same order of operations, so threshold tests decide as the toolkit's do.
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Core>

namespace binpick::bop {

// The depth in mm of a raw PNG value (0 = no data) as the toolkit holds it: float32.
inline float depth_mm_of_raw(std::uint16_t raw, double depth_scale) {
  return float(raw) * float(depth_scale);
}

// The distance from the camera centre of the point at depth z (mm) on pixel (u, v)'s ray, in
// double: ((u - cx) / fx * z)^2 + ((v - cy) / fy * z)^2 + z^2, square-rooted; 0 for z = 0.
inline double distance_of_depth(double z, std::uint32_t u, std::uint32_t v,
                                const Eigen::Matrix3d& K) {
  const double x = (double(u) - K(0, 2)) / K(0, 0) * z;
  const double y = (double(v) - K(1, 2)) / K(1, 1) * z;
  return std::sqrt(x * x + y * y + z * z);
}

}  // namespace binpick::bop
