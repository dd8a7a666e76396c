// An unstructured cloud seen through a virtual pinhole camera at the origin, looking along +z:
// the organised point image that refinement and verification compare poses with
// (pose_refine.hpp), so `detect --cloud` scores poses the way depth images do. Each pixel keeps
// its nearest point; a pixel between points (a gap one pixel wide) takes its nearest neighbour's.
// A cloud is taken as everything the sensor saw: a pixel with no point near it saw nothing in
// front of a far background, so a pose that puts the part there is seen through (unlike a depth
// image's missing pixels, which are neutral).
#pragma once

#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"
#include "host/detect/scene/depth_to_points.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

struct CloudImage {
  bp_camera camera{};  // depth_scale 1
  PointImage points;
  // The same pixels as a depth image of the cloud alone, before gaps and background are filled:
  // each pixel its nearest point's z in units of depth_scale mm (0.1, or 1 beyond 6.5 m), 0
  // where no point falls. What the bin fit and the region mask read (detector_cloud.cpp).
  std::vector<std::uint16_t> depth;
  float depth_scale = 0.1f;
};

// Largest side of the virtual image, pixels.
inline constexpr std::uint32_t kMaxCloudImageSide = 4096;

// Pixels of about `pitch` mm at the cloud's median depth (coarser if the image would exceed
// kMaxCloudImageSide a side). Points at z <= 0 are left out. InputError if no point is in front
// of the camera or pitch is not positive.
CloudImage cloud_point_image(const PointCloud& cloud, float pitch);

}  // namespace binpick
